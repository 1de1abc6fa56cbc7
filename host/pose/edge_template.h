#pragma once
// Edge templates of CAD parts (D2CO's model side): for each viewpoint on a sphere, the
// points of the part's occluding contour and sharp creases as seen from there, with
// the direction of the edge through each point, both in the model's frame. Stored in 3D
// so that any pose projects them exactly; the view they were seen from only decides
// which points are visible.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "host/render/mesh.h"

namespace flexsight {

struct TemplateParams {
  int views = 600;                  // viewpoints on the sphere (Fibonacci spiral)
  int in_plane_steps = 40;          // rotations about the optical axis tried by the search
  int points_per_view = 128;        // edge points kept per view (spread out evenly)
  float crease_degrees = 35.0f;     // a crease: neighbouring surfaces turn by more than this
  int render_size = 400;            // the square template image, pixels; the part spans
                                    // about 70 % of it
  // Throws InputError naming the field for a value out of range.
  void check() const;
};

struct EdgeView {
  Eigen::Matrix3d rotation;              // model -> camera of this viewpoint
  std::vector<Eigen::Vector3f> points;   // model frame, mm, farthest-point order: any
                                         // prefix is itself spread evenly
  std::vector<Eigen::Vector3f> tangents; // unit edge directions, model frame
  // Median depth of the part's visible surface minus the depth of the model's origin
  // (mm, negative: the surface is nearer): turns a measured depth in a box into the
  // depth of the origin.
  float surface_depth_offset = 0.0f;
};

struct PartTemplates {
  int obj_id = 0;
  std::string name;       // the CAD file name, for messages
  float diameter = 0.0f;  // of the mesh, mm
  std::vector<EdgeView> views;
};

struct TemplateSet {
  TemplateParams params;
  std::vector<PartTemplates> parts;
  // The part with this object id, nullptr when there is none.
  const PartTemplates* find(int obj_id) const;
};

// The edge views of one mesh. Deterministic (same bytes for every thread count).
PartTemplates make_part_templates(const Mesh& mesh, int obj_id, const std::string& name,
                                  const TemplateParams& params, int threads = 0);

}  // namespace flexsight

#pragma once
// The coarse step of D2CO in a box: every view and in-plane rotation of a part's
// templates, at the depth the box's stereo depth gives (so at the size the part has
// there), slid over the positions where it covers the box, scored by the mean
// directional chamfer distance of its edge points. The best few become candidates for
// the refinement.
#include <opencv2/core.hpp>
#include <vector>

#include "host/pose/dcd_tensor.h"
#include "host/pose/edge_template.h"
#include "host/render/raycaster.h"

namespace flexsight {

struct SearchParams {
  int coarse_points = 32;        // edge points per template scored in the search (the
                                 // first of the farthest-point order: an even subset)
  int grid_positions = 4;        // per axis: every template is first tried on a grid
                                 // this fine over the positions where it covers the box
  int refined_templates = 64;    // the best templates of the grid are then tried
  double position_step = 1.0;    // this many pixels apart around their best position
  double min_cover = 0.8;        // a template at least this fraction of the box size
  double max_area_ratio = 4.0;   // and at most this times the box's area (occlusion)
  int candidates = 8;            // kept for the refinement, best first
  double distinct_degrees = 12.0;  // candidates closer than this in rotation and
  double distinct_pixels = 6.0;    // this in position are one hypothesis
  void check() const;
};

struct PoseCandidate {
  Pose pose;            // model -> camera
  double cost = 0.0;    // mean chamfer distance of the coarse points, pixels
  int view = 0;         // index into PartTemplates::views
  int in_plane = 0;     // step of the rotation about the optical axis
};

// `tensor` covers the image region starting at `tensor_origin` (image pixels); `box` is
// in image pixels; `surface_depth` the depth (mm) of the part's visible surface in the
// box. Candidates best (lowest cost) first; fewer when fewer templates fit the box.
std::vector<PoseCandidate> search_templates(const PartTemplates& part, int in_plane_steps,
                                            const DcdTensor& tensor, cv::Point tensor_origin,
                                            const PinholeCamera& camera, const cv::Rect& box,
                                            double surface_depth, const SearchParams& params);

// The pose that puts the model's origin at depth `depth` on the ray through pixel
// `origin_pixel`, turned so that it looks as it does with rotation `on_axis_rotation`
// on the optical axis (the template's appearance moves with the ray).
Pose pose_on_ray(const Eigen::Matrix3d& on_axis_rotation, const Eigen::Vector2d& origin_pixel,
                 double depth, const PinholeCamera& camera);

}  // namespace flexsight

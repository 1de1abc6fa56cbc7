#pragma once
// Ray casting of posed CAD parts with Embree: per pixel depth, instance id, normal and
// hit point in the camera frame, and per-instance masks (visible and amodal). The one
// way this project makes images of parts; detection, pose and bin simulation build on it.
//
// Frames follow OpenCV: the camera looks along +z, x to the right, y down, in mm. A
// pixel (u, v) is the point u, v of the image plane (pixel centres on integer
// coordinates, as cv::projectPoints), so its ray is ((u - cx) / fx, (v - cy) / fy, 1).
#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "host/geometry/pinhole_camera.h"
#include "host/geometry/pose.h"
#include "host/render/mesh.h"

namespace flexsight {

// How a surface looks under the shading of host/render/shading.h.
struct Material {
  // Diffuse reflectance per channel (linear RGB, 0..1).
  Eigen::Vector3f albedo{0.6f, 0.6f, 0.6f};
  // Weight and exponent of the Blinn-Phong highlight: the T-LESS parts are moulded
  // plastic, with a broad, weak highlight.
  float specular = 0.25f;
  float shininess = 30.0f;
};

struct Instance {
  int mesh = 0;  // index returned by RenderScene::add_mesh
  Pose pose;
  Material material;
};

// Meshes, each with its own bounding volume hierarchy built once, and instances of them
// at poses; Embree traces the instances without copying their triangles, so a bin of
// twenty copies of one part costs one part's memory. (Not "Scene": host/eval's Scene is
// a data set's stereo scene, in the same namespace.)
class RenderScene {
 public:
  RenderScene();
  ~RenderScene();
  RenderScene(RenderScene&&) noexcept;
  RenderScene& operator=(RenderScene&&) noexcept;
  RenderScene(const RenderScene&) = delete;
  RenderScene& operator=(const RenderScene&) = delete;

  // Builds the mesh's hierarchy now and returns its index.
  int add_mesh(std::shared_ptr<const Mesh> mesh);
  // Places mesh `mesh` at `pose`; returns the instance id (0, 1, ... in the order of the
  // calls), which the instance image holds.
  int add_instance(int mesh, const Pose& pose, const Material& material = {});
  void set_pose(int instance, const Pose& pose);
  void set_material(int instance, const Material& material);
  // Builds the instances' hierarchy. Needed after adding instances or changing poses
  // and before casting rays (which throw std::logic_error otherwise).
  void commit();
  bool committed() const;

  int mesh_count() const;
  int instance_count() const;
  const Mesh& mesh(int index) const;
  const Instance& instance(int id) const;
  // The Embree scene of the instances (committed), for comparisons with raw Embree.
  RTCScene embree_scene() const;
  // The Embree scene of one mesh in its own frame.
  RTCScene embree_mesh_scene(int mesh) const;
  // The Embree scene holding instance `instance` alone, at its pose (committed).
  RTCScene embree_instance_scene(int instance) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct RaycastOptions {
  // OpenMP threads over 16x16-pixel tiles; 0 takes OpenMP's default. The images are the
  // same bytes for every thread count.
  int threads = 0;
  // raycast() only: when not empty, only the pixels inside at least one of these
  // rectangles are written, the others left as where no surface is, and only the 4x4
  // packets of rays that meet a rectangle are cast. For a caller that knows where
  // surfaces can be, such as the union of the instances' projected boxes (rays outside
  // it would all miss). The pixels written are the same bytes as without areas (the
  // packets cast are the same). amodal_masks casts each instance's own box anyway.
  std::vector<cv::Rect> areas;
};

struct RaycastImages {
  cv::Mat depth;             // CV_32FC1: z of the hit point in mm; 0 where no surface
  cv::Mat instance;          // CV_32SC1: instance id; -1 where no surface
  cv::Mat normal;            // CV_32FC3: unit shading normal, camera frame, turned to face
                             // the camera; 0 where no surface
  cv::Mat geometric_normal;  // CV_32FC3: unit normal of the triangle hit, facing the camera
  cv::Mat point;             // CV_32FC3: hit point, camera frame, mm; 0 where no surface
};

// Casts one ray per pixel through the instances, closest hit first. Surfaces are two
// sided: a ray that meets a triangle from behind (an open mesh seen from inside) reports
// the normals turned towards the camera.
RaycastImages raycast(const RenderScene& scene, const PinholeCamera& camera,
                      const RaycastOptions& options = {});

// The mask of each instance as if it were alone (amodal: including what others hide),
// CV_8UC1 with 255 on the instance. Only the pixels within the projection of the
// instance's box are cast.
std::vector<cv::Mat> amodal_masks(const RenderScene& scene, const PinholeCamera& camera,
                                  const RaycastOptions& options = {});

// The pixels whose centres can fall on `mesh` at `pose`: the box of its bounding box's
// projected corners, one pixel wider against rounding, clipped to the image; the whole
// image when a corner is not in front of the camera.
cv::Rect projected_area(const Mesh& mesh, const Pose& pose, const PinholeCamera& camera);

// The pixels where `instance` is the closest surface, CV_8UC1 255 / 0.
cv::Mat visible_mask(const RaycastImages& images, int instance);

}  // namespace flexsight

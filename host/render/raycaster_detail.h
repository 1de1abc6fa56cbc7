#pragma once
// What the ray caster and the shading share inside the module: the camera's ray
// directions, the instances' data read per hit, and the ray set-up.
#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <vector>

#include "host/render/raycaster.h"

namespace flexsight::render_detail {

// Ray direction of pixel (u, v): (dx[u], dy[v], 1), so that the hit parameter t is the
// depth z itself.
struct CameraRays {
  explicit CameraRays(const PinholeCamera& camera);  // checks the camera
  std::vector<float> dx, dy;
};

// Per instance, what a hit needs: its mesh and its rotation in float. Throws
// std::logic_error when the scene is not committed.
struct SceneView {
  struct Entry {
    const Mesh* mesh;
    Eigen::Matrix3f R;
  };
  explicit SceneView(const Scene& scene);
  std::vector<Entry> instances;
};

// A ray from `origin` along `direction` over [0, inf), no hit yet.
void init_ray(RTCRayHit& ray_hit, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction);

}  // namespace flexsight::render_detail

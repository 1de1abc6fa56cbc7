#pragma once
// The scene `flexsight render` shows: CAD parts side by side, turned alike, in front of
// a floor facing the camera, as in a bin seen from above.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "host/render/mesh.h"
#include "host/render/raycaster.h"

namespace flexsight {

struct PartRowLayout {
  // Distance of the parts from the camera (mm); 0: the row fills about 60 % of the
  // image width.
  double distance = 0.0;
  // The parts' turn in degrees about the camera's x, y, z axes, in that order.
  Eigen::Vector3d rotation_degrees{30.0, -40.0, 0.0};
  // A matte floor just behind the deepest part.
  bool floor = true;
};

struct PartRow {
  RenderScene scene;       // committed: instance i is part i, the floor last
  double distance = 0.0;   // of the parts from the camera (mm)
  Eigen::Vector3f light;   // above and to the left of the camera, a distance's height above the parts
};

// The parts of `meshes` in a row centred on the optical axis, each tinted by
// tinted_grey(seed, i).
PartRow compose_part_row(const std::vector<std::shared_ptr<const Mesh>>& meshes, const PinholeCamera& camera,
                         const PartRowLayout& layout, std::uint32_t seed);

// 8-bit: part i (instance i below `parts`) as i + 1, anything else 0.
cv::Mat part_mask(const cv::Mat& instance, int parts);

}  // namespace flexsight

#include "host/geometry/pinhole_camera.h"

#include <cmath>
#include <string>

#include "host/io/input_error.h"

namespace flexsight {

void PinholeCamera::check() const {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (width <= 0 || height <= 0) {
    throw InputError("camera", "image size " + std::to_string(width) + "x" +
                                   std::to_string(height) + " is not positive");
  }
  if (!positive(fx) || !positive(fy)) {
    throw InputError("camera", "focal lengths fx = " + std::to_string(fx) +
                                   ", fy = " + std::to_string(fy) + " must be positive");
  }
  if (!std::isfinite(cx) || !std::isfinite(cy)) {
    throw InputError("camera", "principal point is not finite");
  }
}

Eigen::Vector2d PinholeCamera::project(const Eigen::Vector3d& p) const {
  return {fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy};
}

PinholeCamera centred_camera(int width, int height, double focal) {
  PinholeCamera camera;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = focal;
  camera.cx = 0.5 * (width - 1);
  camera.cy = 0.5 * (height - 1);
  return camera;
}

}  // namespace flexsight

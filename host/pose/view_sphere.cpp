#include "host/pose/view_sphere.h"

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>

namespace flexsight {

std::vector<Eigen::Vector3d> fibonacci_sphere(int n) {
  if (n < 1) throw std::invalid_argument("fibonacci_sphere: n must be positive");
  const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
  std::vector<Eigen::Vector3d> points;
  points.reserve(n);
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double radius = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden_angle * i;
    points.emplace_back(radius * std::cos(phi), radius * std::sin(phi), z);
  }
  return points;
}

Eigen::Matrix3d look_at_origin(const Eigen::Vector3d& direction) {
  const Eigen::Vector3d z_axis = -direction.normalized();
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  if (std::abs(z_axis.dot(up)) > 0.99) up = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d x_axis = up.cross(z_axis).normalized();
  const Eigen::Vector3d y_axis = z_axis.cross(x_axis);
  Eigen::Matrix3d R;
  R.row(0) = x_axis.transpose();
  R.row(1) = y_axis.transpose();
  R.row(2) = z_axis.transpose();
  return R;
}

}  // namespace flexsight

#include "host/pose/pose_math.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace flexsight {

Eigen::Matrix3d rotation_from_axis_angle(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

double rotation_angle_degrees(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const double cosine = std::clamp(((a.transpose() * b).trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(cosine) * 180.0 / M_PI;
}

std::vector<Eigen::Vector3f> transform_points(const Pose& pose,
                                              const std::vector<Eigen::Vector3f>& points) {
  const Eigen::Matrix3f R = pose.R.cast<float>();
  const Eigen::Vector3f t = pose.t.cast<float>();
  std::vector<Eigen::Vector3f> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(R * p + t);
  return out;
}

Pose compose(const Pose& delta, const Pose& pose) {
  Pose out;
  out.R = delta.R * pose.R;
  out.t = delta.R * pose.t + delta.t;
  return out;
}

}  // namespace flexsight

#pragma once
// Small rigid-motion helpers the pose module shares: the rotation of an axis-angle
// vector, the angle between two rotations, and a pose applied to points.
#include <Eigen/Core>
#include <vector>

#include "host/render/raycaster.h"

namespace flexsight {

// The rotation of angle |w| (radians) about w / |w| (Rodrigues); identity for w = 0.
Eigen::Matrix3d rotation_from_axis_angle(const Eigen::Vector3d& w);

// The angle in degrees of the rotation that takes a to b (0..180).
double rotation_angle_degrees(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

// R x + t for each point.
std::vector<Eigen::Vector3f> transform_points(const Pose& pose,
                                              const std::vector<Eigen::Vector3f>& points);

// The pose of `pose` followed by `delta` (applied in the camera frame): delta.R pose.R,
// delta.R pose.t + delta.t.
Pose compose(const Pose& delta, const Pose& pose);

}  // namespace flexsight

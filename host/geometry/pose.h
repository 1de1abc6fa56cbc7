#pragma once
// A rigid pose: the one transform type of the renderer, the simulator and the pose
// estimator.
#include <Eigen/Core>

namespace flexsight {

// A model point x appears at R x + t in the camera frame (mm).
struct Pose {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

}  // namespace flexsight

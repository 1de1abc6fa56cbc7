#pragma once
// Viewpoints spread evenly over a sphere, and the camera rotation that looks from one of
// them at the model's origin: the out-of-plane part of a template's pose.
#include <Eigen/Core>
#include <vector>

namespace flexsight {

// n unit vectors on a Fibonacci spiral: the most even spread that needs no iteration
// (neighbours within a few percent of the mean spacing, no cluster at the poles).
std::vector<Eigen::Vector3d> fibonacci_sphere(int n);

// The rotation model -> camera of a camera at `direction` (unit vector from the model's
// origin to the camera, model frame) looking at the origin: the camera's z axis is
// -direction, its x axis horizontal with respect to the model's z axis where it can be
// (the model's y axis for a view straight along z).
Eigen::Matrix3d look_at_origin(const Eigen::Vector3d& direction);

}  // namespace flexsight

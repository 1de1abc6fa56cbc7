#pragma once
// D2CO's refinement: the 6 degrees of freedom of a pose moved by Levenberg-Marquardt so
// that the template's edge points, projected, fall on image edges of their direction:
// the sum of squared directional chamfer distances, read from the tensor with bilinear
// interpolation and its derivatives.
//
// Ceres (libceres-dev) solves it rather than Eigen's unsupported LevenbergMarquardt:
// automatic derivatives through the rotation and projection (only the tensor lookup
// supplies its own), robust losses that keep edge points caught on clutter from
// dragging the pose, and a maintained solver with clear termination reports.
#include <opencv2/core.hpp>
#include <vector>

#include "host/pose/dcd_tensor.h"
#include "host/render/raycaster.h"

namespace flexsight {

struct DcdRefineParams {
  int max_iterations = 30;
  double huber_pixels = 4.0;  // residuals beyond this count linearly
  void check() const;
};

struct DcdRefineResult {
  Pose pose;
  double initial_cost = 0.0;  // mean chamfer distance of the points, pixels
  double final_cost = 0.0;
  int iterations = 0;
};

// The mean directional chamfer distance of `points` (with `tangents`, model frame) at
// `pose`; the tensor covers the image from `tensor_origin` on.
double mean_chamfer(const std::vector<Eigen::Vector3f>& points,
                    const std::vector<Eigen::Vector3f>& tangents, const Pose& pose,
                    const PinholeCamera& camera, const DcdTensor& tensor, cv::Point tensor_origin);

DcdRefineResult refine_on_dcd(const std::vector<Eigen::Vector3f>& points,
                              const std::vector<Eigen::Vector3f>& tangents, const Pose& initial,
                              const PinholeCamera& camera, const DcdTensor& tensor,
                              cv::Point tensor_origin, const DcdRefineParams& params);

}  // namespace flexsight

#include "host/geometry/depth_from_disparity.h"

#include <cmath>
#include <limits>

namespace flexsight {
namespace {

bool converted(float d, DepthRule::Disparities which) {
  switch (which) {
    case DepthRule::Disparities::kAll: return true;
    case DepthRule::Disparities::kNonNegative: return std::isfinite(d) && d >= 0.0f;
    case DepthRule::Disparities::kPositive: return std::isfinite(d) && d > 0.0f;
  }
  return false;
}

}  // namespace

DepthRule DepthRule::cloud() {
  return {Disparities::kNonNegative, false, std::numeric_limits<float>::quiet_NaN()};
}

cv::Mat depth_from_disparity(const cv::Mat& disparity, const StereoCamera& camera,
                             double metres_per_unit_out, const DepthRule& rule) {
  cv::Mat depth(disparity.size(), CV_32FC1, cv::Scalar(rule.no_depth));
  // For the units calibration files give (mm, cm, m) and millimetres out, this is the
  // same double as metres_per_unit * 1000.
  const double scale = camera.metres_per_unit / metres_per_unit_out;
  for (int y = 0; y < disparity.rows; ++y) {
    for (int x = 0; x < disparity.cols; ++x) {
      const float d = disparity.at<float>(y, x);
      if (!converted(d, rule.disparities)) continue;
      const double z = camera.depth(d) * scale;
      if (rule.positive_depth_only && !(std::isfinite(z) && z > 0.0)) continue;
      depth.at<float>(y, x) = static_cast<float>(z);
    }
  }
  return depth;
}

}  // namespace flexsight

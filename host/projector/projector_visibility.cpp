#include "host/projector/projector_visibility.h"

#include <cmath>
#include <limits>

namespace flexsight {

StereoVisibility::StereoVisibility(const cv::Mat& raw_left, const cv::Mat& raw_right, const LeftCamera& camera,
                                   const ProjectorCalib& projector, const VirtualView& view, float tolerance)
    : tx_over_b_(projector.t[0] / camera.baseline_mm), doffs_(camera.doffs), view_(&view), tolerance_(tolerance) {
  constexpr float kConsistent = 1.0f;  // px between the two views' disparities
  const float nan = std::numeric_limits<float>::quiet_NaN();
  right_consistent_ = cv::Mat(raw_right.size(), CV_32FC1, cv::Scalar(nan));
  nearest_ = cv::Mat(view.samples.size(), CV_32FC1, cv::Scalar(-std::numeric_limits<float>::infinity()));
  for (int v = 0; v < raw_left.rows; ++v) {
    for (int x = 0; x < raw_left.cols; ++x) {
      const float d = raw_left.at<float>(v, x);
      if (!std::isfinite(d) || d < 0) continue;
      const int xr = int(std::lround(x - d));
      if (xr < 0 || xr >= raw_right.cols) continue;
      const float dr = raw_right.at<float>(v, xr);
      if (!std::isfinite(dr) || std::abs(dr - d) > kConsistent) continue;
      right_consistent_.at<float>(v, xr) = dr;
      const int j = view.column(x + tx_over_b_ * (d + doffs_));
      if (j < 0 || j >= nearest_.cols) continue;
      float& slot = nearest_.at<float>(v, j);
      slot = std::max(slot, d);
    }
  }
}

bool StereoVisibility::in_free_space(int u, int v, double d) const {
  const int xr = int(std::lround(u - d));
  if (xr < 0 || xr >= right_consistent_.cols) return false;
  const float dr = right_consistent_.at<float>(v, xr);
  return std::isfinite(dr) && dr < d - tolerance_;
}

bool StereoVisibility::in_shadow(int u, int v, double d) const {
  const int j = view_->column(u + tx_over_b_ * (d + doffs_));
  for (int k = j - 1; k <= j + 1; ++k) {  // a surface samples the view every other column or so
    if (k >= 0 && k < nearest_.cols && nearest_.at<float>(v, k) > d + tolerance_) return true;
  }
  return false;
}

bool StereoVisibility::possible(int u, int v, double d) const {
  return !in_free_space(u, v, d) && !in_shadow(u, v, d);
}

}  // namespace flexsight

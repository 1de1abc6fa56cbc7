#include "host/stereo/disparity_upsampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace flexsight {

cv::Mat upsample_disparity(const cv::Mat& disparity_small, const cv::Mat& planes_small, cv::Size full) {
  if (disparity_small.type() != CV_32FC1 || planes_small.type() != CV_32FC3 ||
      disparity_small.size() != planes_small.size() || disparity_small.empty()) {
    throw std::invalid_argument("upsample_disparity: a CV_32FC1 disparity and CV_32FC3 planes of one size");
  }
  const cv::Size small = disparity_small.size();
  const double sx = static_cast<double>(full.width) / small.width;
  const double sy = static_cast<double>(full.height) / small.height;
  cv::Mat disparity(full, CV_32FC1);
  for (int y = 0; y < full.height; ++y) {
    // Pixel centres: full-size pixel y covers small rows (y .. y + 1) / sy.
    const double ys = (y + 0.5) / sy - 0.5;
    const int py = std::clamp(static_cast<int>(std::lround(ys)), 0, small.height - 1);
    for (int x = 0; x < full.width; ++x) {
      const double xs = (x + 0.5) / sx - 0.5;
      const int px = std::clamp(static_cast<int>(std::lround(xs)), 0, small.width - 1);
      const float d = disparity_small.at<float>(py, px);
      const cv::Vec3f plane = planes_small.at<cv::Vec3f>(py, px);
      const double moved = d + plane[0] * (xs - px) + plane[1] * (ys - py);
      disparity.at<float>(y, x) = static_cast<float>((std::isfinite(moved) ? moved : d) * sx);
    }
  }
  return disparity;
}

}  // namespace flexsight

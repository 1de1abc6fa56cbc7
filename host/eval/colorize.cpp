#include "host/eval/colorize.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace flexsight {

namespace {

bool has_result(float disparity) { return std::isfinite(disparity) && disparity >= 0.0f; }

void require_disparity(const cv::Mat& image, const char* what) {
  if (image.empty() || image.type() != CV_32FC1) {
    throw std::invalid_argument(std::string(what) + " must be a non-empty CV_32FC1 image");
  }
}

// Error-map palette, in RGB.
const cv::Vec3b kUnknownColor(0, 0, 0);
const cv::Vec3b kMissingColor(255, 0, 255);

// Good pixels: bright green at zero error fading to a darker green at the threshold,
// so the eye can still see how close to the limit a region is.
cv::Vec3b good_color(double error, double threshold) {
  const double t = std::min(error / threshold, 1.0);
  return cv::Vec3b(0, cv::saturate_cast<uchar>(255.0 - 127.0 * t), 0);
}

// Bad pixels: yellow just above the threshold to red at 4 * threshold and beyond.
cv::Vec3b bad_color(double error, double threshold) {
  const double t = std::clamp((error - threshold) / (3.0 * threshold), 0.0, 1.0);
  return cv::Vec3b(255, cv::saturate_cast<uchar>(255.0 * (1.0 - t)), 0);
}

cv::Vec3b darker(const cv::Vec3b& color) {
  return cv::Vec3b(color[0] / 2, color[1] / 2, color[2] / 2);
}

cv::Vec3b error_color(float disparity, float truth, double threshold) {
  if (!std::isfinite(truth)) return kUnknownColor;
  if (!has_result(disparity)) return kMissingColor;
  const double error = std::fabs(static_cast<double>(disparity) - truth);
  // Same rule as the metrics: exactly at the threshold is still good.
  return error <= threshold ? good_color(error, threshold) : bad_color(error, threshold);
}

}  // namespace

cv::Mat colorize_disparity(const cv::Mat& disparity, float max_disparity) {
  require_disparity(disparity, "colorize_disparity: disparity");
  if (!(std::isfinite(max_disparity) && max_disparity > 0.0f)) {
    throw std::invalid_argument("colorize_disparity: max_disparity must be positive, got " +
                                std::to_string(max_disparity));
  }
  // Quantise to the 256 entries of the colormap; values past the range saturate.
  cv::Mat levels(disparity.size(), CV_8UC1);
  cv::Mat valid(disparity.size(), CV_8UC1);
  for (int y = 0; y < disparity.rows; ++y) {
    const float* d = disparity.ptr<float>(y);
    uchar* level = levels.ptr<uchar>(y);
    uchar* ok = valid.ptr<uchar>(y);
    for (int x = 0; x < disparity.cols; ++x) {
      ok[x] = has_result(d[x]) ? 255 : 0;
      level[x] = ok[x] ? cv::saturate_cast<uchar>(255.0 * d[x] / max_disparity) : 0;
    }
  }
  cv::Mat bgr;
  cv::applyColorMap(levels, bgr, cv::COLORMAP_TURBO);
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);  // OpenCV colormaps are BGR, our images RGB
  rgb.setTo(cv::Scalar::all(0), valid == 0);
  return rgb;
}

cv::Mat colorize_confidence(const cv::Mat& confidence) {
  require_disparity(confidence, "colorize_confidence: confidence");
  cv::Mat levels(confidence.size(), CV_8UC1);
  cv::Mat valid(confidence.size(), CV_8UC1);
  for (int y = 0; y < confidence.rows; ++y) {
    const float* c = confidence.ptr<float>(y);
    for (int x = 0; x < confidence.cols; ++x) {
      valid.at<uchar>(y, x) = std::isfinite(c[x]) ? 255 : 0;
      levels.at<uchar>(y, x) = std::isfinite(c[x]) ? cv::saturate_cast<uchar>(255.0 * c[x]) : 0;
    }
  }
  cv::Mat bgr, rgb;
  cv::applyColorMap(levels, bgr, cv::COLORMAP_VIRIDIS);
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  rgb.setTo(cv::Scalar::all(0), valid == 0);
  return rgb;
}

cv::Mat error_map(const cv::Mat& disparity, const cv::Mat& ground_truth,
                  const cv::Mat& nonocc_mask, float threshold) {
  require_disparity(disparity, "error_map: disparity");
  require_disparity(ground_truth, "error_map: ground truth");
  if (ground_truth.size() != disparity.size()) {
    throw std::invalid_argument("error_map: ground truth and disparity differ in size");
  }
  if (!nonocc_mask.empty() &&
      (nonocc_mask.type() != CV_8UC1 || nonocc_mask.size() != disparity.size())) {
    throw std::invalid_argument("error_map: mask must be CV_8UC1 of the disparity's size");
  }
  if (!(std::isfinite(threshold) && threshold > 0.0f)) {
    throw std::invalid_argument("error_map: threshold must be positive");
  }
  cv::Mat rgb(disparity.size(), CV_8UC3);
  for (int y = 0; y < disparity.rows; ++y) {
    const float* d = disparity.ptr<float>(y);
    const float* gt = ground_truth.ptr<float>(y);
    const uchar* mask = nonocc_mask.empty() ? nullptr : nonocc_mask.ptr<uchar>(y);
    cv::Vec3b* out = rgb.ptr<cv::Vec3b>(y);
    for (int x = 0; x < disparity.cols; ++x) {
      const cv::Vec3b color = error_color(d[x], gt[x], threshold);
      const bool occluded = mask && mask[x] != 255;
      out[x] = occluded ? darker(color) : color;
    }
  }
  return rgb;
}

}  // namespace flexsight

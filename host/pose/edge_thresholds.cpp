#include "host/pose/edge_thresholds.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

// The grey level below which `fraction` of the pixels lie (histogram, CV_8UC1).
int percentile(const cv::Mat& grey, double fraction) {
  int histogram[256] = {};
  for (int y = 0; y < grey.rows; ++y) {
    const std::uint8_t* row = grey.ptr<std::uint8_t>(y);
    for (int x = 0; x < grey.cols; ++x) ++histogram[row[x]];
  }
  const double target = fraction * static_cast<double>(grey.total());
  double seen = 0.0;
  for (int level = 0; level < 256; ++level) {
    seen += histogram[level];
    if (seen >= target) return level;
  }
  return 255;
}

// Median of |v| over both derivative images (a histogram of the absolute values, which
// the 3x3 Sobel of 8-bit grey bounds by 1020).
double median_absolute(const cv::Mat& dx, const cv::Mat& dy) {
  std::vector<std::int64_t> histogram(1021, 0);
  for (const cv::Mat* d : {&dx, &dy}) {
    for (int y = 0; y < d->rows; ++y) {
      const std::int16_t* row = d->ptr<std::int16_t>(y);
      for (int x = 0; x < d->cols; ++x) ++histogram[std::min(1020, std::abs(int(row[x])))];
    }
  }
  const std::int64_t half = static_cast<std::int64_t>(dx.total() + dy.total()) / 2;
  std::int64_t seen = 0;
  for (int value = 0; value <= 1020; ++value) {
    seen += histogram[value];
    if (seen > half) return value;
  }
  return 1020.0;
}

}  // namespace

void stretch_contrast(cv::Mat& grey) {
  if (grey.empty()) return;
  const int low = percentile(grey, 0.02), high = percentile(grey, 0.98);
  if (high - low < 8) return;
  grey.convertTo(grey, CV_8U, 255.0 / (high - low), -255.0 * low / (high - low));
}

CannyThresholds above_gradient_noise(CannyThresholds thresholds, const cv::Mat& dx, const cv::Mat& dy) {
  if (dx.empty()) return thresholds;
  const double sigma = median_absolute(dx, dy) / 0.6745;
  thresholds.high = std::max(thresholds.high, 4.0 * sigma);
  thresholds.low = std::max(thresholds.low, 2.0 * sigma);
  return thresholds;
}

DcdParams::EdgeThresholds edge_thresholds_named(const std::string& name, const std::string& option) {
  using E = DcdParams::EdgeThresholds;
  if (name == "fixed") return E::kFixed;
  if (name == "contrast") return E::kContrast;
  if (name == "noise") return E::kNoise;
  if (name == "contrast+noise") return E::kContrastAndNoise;
  throw InputError("option " + option, "expected fixed, contrast, noise or contrast+noise, got '" + name + "'");
}

}  // namespace flexsight

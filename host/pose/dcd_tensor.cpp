#include "host/pose/dcd_tensor.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "host/io/input_error.h"
#include "host/pose/edge_thresholds.h"

namespace flexsight {
namespace {

// The angle folded into [0, pi) (pi itself, reached by rounding, is the same
// direction as 0).
double fold_orientation(double radians) {
  double folded = std::fmod(radians, M_PI);
  if (folded < 0.0) folded += M_PI;
  return folded >= M_PI ? 0.0 : folded;
}

// The same as a float for the edge map: a value just below pi can round up to float(pi),
// which lies above pi; such directions become 0 too.
float fold_orientation_float(double radians) {
  const float out = static_cast<float>(fold_orientation(radians));
  return out >= static_cast<float>(M_PI) ? 0.0f : out;
}

void require(bool ok, const std::string& field, const std::string& problem) {
  if (!ok) throw InputError("dcd " + field, problem);
}

// The roi grown by `margin` on every side, clipped to the image.
cv::Rect grown(const cv::Rect& roi, int margin, const cv::Size& image) {
  const cv::Rect outer(roi.x - margin, roi.y - margin, roi.width + 2 * margin,
                       roi.height + 2 * margin);
  return outer & cv::Rect(cv::Point(0, 0), image);
}

// The relaxations of the orientation axis, in place: bin b takes the cost of its
// neighbour `direction` bins away plus one step, around the circle twice, so that every
// bin has seen every other one along this direction (a chain of up to bins - 1 steps
// that may start anywhere, wrap-around included, fits in two turns; one and a half
// would do, the other direction covering the far half of the circle, but the relaxation
// is a fifth of the build and two turns need no such argument).
void relax_around_the_circle(std::vector<cv::Mat>& layers, int direction, float step) {
  const int bins = static_cast<int>(layers.size());
  const size_t cells = layers.front().total();
  for (int i = 0; i < 2 * bins; ++i) {
    const int b = direction > 0 ? i % bins : bins - 1 - i % bins;
    const float* from = layers[(b - direction + bins) % bins].ptr<float>();
    float* to = layers[b].ptr<float>();
    for (size_t k = 0; k < cells; ++k) to[k] = std::min(to[k], from[k] + step);
  }
}

}  // namespace

void DcdParams::check() const {
  require(orientation_bins >= 1, "orientation_bins",
          "must be at least 1, got " + std::to_string(orientation_bins));
  require(std::isfinite(orientation_weight) && orientation_weight >= 0.0f, "orientation_weight",
          "must be finite and >= 0, got " + std::to_string(orientation_weight));
  require(std::isfinite(max_distance) && max_distance > 0.0f, "max_distance",
          "must be finite and > 0, got " + std::to_string(max_distance));
  require(std::isfinite(canny_low) && canny_low >= 0.0, "canny_low",
          "must be finite and >= 0, got " + std::to_string(canny_low));
  require(std::isfinite(canny_high) && canny_high >= canny_low, "canny_high",
          "must be finite and >= canny_low, got " + std::to_string(canny_high));
  require(std::isfinite(blur_sigma) && blur_sigma >= 0.0, "blur_sigma",
          "must be finite and >= 0, got " + std::to_string(blur_sigma));
}

EdgeMap detect_edges(const cv::Mat& image, const cv::Rect& roi, const DcdParams& params) {
  params.check();
  if (image.type() != CV_8UC1 && image.type() != CV_8UC3) {
    throw InputError("edge detection", "the image must be 8-bit grey or BGR");
  }
  const cv::Rect inner = roi & cv::Rect(0, 0, image.cols, image.rows);
  if (inner.empty()) {
    throw InputError("edge detection",
                     "roi " + std::to_string(roi.width) + "x" + std::to_string(roi.height) +
                         " at (" + std::to_string(roi.x) + ", " + std::to_string(roi.y) +
                         ") does not overlap the " + std::to_string(image.cols) + "x" +
                         std::to_string(image.rows) + " image");
  }
  // The blur reaches 3 sigma (OpenCV's kernel for 8-bit images), the Sobel derivatives
  // one pixel further, Canny's non-maximum suppression one more.
  const int margin = static_cast<int>(std::ceil(3.0 * params.blur_sigma)) + 2;
  const cv::Rect outer = grown(inner, margin, image.size());

  cv::Mat grey;
  if (image.channels() == 3) {
    cv::cvtColor(image(outer), grey, cv::COLOR_BGR2GRAY);
  } else {
    grey = image(outer).clone();
  }
  const bool stretch = params.thresholds == DcdParams::EdgeThresholds::kContrast ||
                       params.thresholds == DcdParams::EdgeThresholds::kContrastAndNoise;
  if (stretch) stretch_contrast(grey);
  if (params.blur_sigma > 0.0) {
    cv::GaussianBlur(grey, grey, cv::Size(), params.blur_sigma, params.blur_sigma);
  }
  // Canny from our own derivatives, so that the directions below are those of the
  // gradients Canny thresholded.
  cv::Mat dx, dy, edges;
  cv::Sobel(grey, dx, CV_16S, 1, 0, 3);
  cv::Sobel(grey, dy, CV_16S, 0, 1, 3);
  CannyThresholds canny{params.canny_low, params.canny_high};
  if (params.thresholds == DcdParams::EdgeThresholds::kNoise ||
      params.thresholds == DcdParams::EdgeThresholds::kContrastAndNoise) {
    canny = above_gradient_noise(canny, dx, dy);
  }
  cv::Canny(dx, dy, edges, canny.low, canny.high, /*L2gradient=*/true);

  const cv::Rect crop(inner.tl() - outer.tl(), inner.size());
  EdgeMap out;
  out.mask = edges(crop).clone();
  out.orientation = cv::Mat::zeros(inner.size(), CV_32FC1);
  for (int y = 0; y < crop.height; ++y) {
    const std::uint8_t* mask = out.mask.ptr<std::uint8_t>(y);
    const std::int16_t* gx = dx.ptr<std::int16_t>(y + crop.y) + crop.x;
    const std::int16_t* gy = dy.ptr<std::int16_t>(y + crop.y) + crop.x;
    float* orientation = out.orientation.ptr<float>(y);
    for (int x = 0; x < crop.width; ++x) {
      if (mask[x] == 0) continue;
      // The tangent is perpendicular to the gradient.
      orientation[x] = fold_orientation_float(std::atan2(double(gy[x]), double(gx[x])) + M_PI / 2.0);
    }
  }
  return out;
}

DcdTensor::DcdTensor(const EdgeMap& edges, const DcdParams& params) {
  params.check();
  if (edges.mask.empty() || edges.mask.type() != CV_8UC1 ||
      edges.orientation.type() != CV_32FC1 || edges.mask.size() != edges.orientation.size()) {
    throw std::invalid_argument(
        "DcdTensor: the edge map needs a CV_8UC1 mask and a CV_32FC1 orientation of one size");
  }
  bins_ = params.orientation_bins;
  max_distance_ = params.max_distance;
  const cv::Size size = edges.mask.size();

  // One image per bin that is zero on the bin's edge pixels, which is what
  // cv::distanceTransform measures the distance to. Bins without an edge stay empty.
  std::vector<cv::Mat> sources(bins_);
  for (int y = 0; y < size.height; ++y) {
    const std::uint8_t* mask = edges.mask.ptr<std::uint8_t>(y);
    const float* orientation = edges.orientation.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      if (mask[x] == 0) continue;
      cv::Mat& source = sources[bin_of(orientation[x])];
      if (source.empty()) source = cv::Mat(size, CV_8UC1, cv::Scalar(255));
      source.at<std::uint8_t>(y, x) = 0;
    }
  }

  // The exact Euclidean distance to the nearest edge of each bin (DIST_MASK_PRECISE is
  // Felzenszwalb's exact transform), saturated. Saturating before the orientation
  // recursion gives the same cells as after it: a bin's own saturated value is always
  // one of the candidates.
  layers_.resize(bins_);
  for (int b = 0; b < bins_; ++b) {
    if (sources[b].empty()) {
      layers_[b] = cv::Mat(size, CV_32FC1, cv::Scalar(max_distance_));
      continue;
    }
    cv::distanceTransform(sources[b], layers_[b], cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    cv::min(layers_[b], max_distance_, layers_[b]);
    // The recursion below walks the layers as flat arrays.
    CV_Assert(layers_[b].isContinuous());
  }

  // The orientation penalty: the cheapest way to a bin is from its neighbour on one
  // side or the other plus one step (the cost is linear in the circular bin distance),
  // so a forward and a backward recursion around the circle give the minimum over all
  // bins (D2CO, section 3).
  if (bins_ > 1) {
    const float step = static_cast<float>(params.orientation_weight * M_PI / bins_);
    relax_around_the_circle(layers_, +1, step);
    relax_around_the_circle(layers_, -1, step);
  }
}

int DcdTensor::width() const { return layers_.front().cols; }
int DcdTensor::height() const { return layers_.front().rows; }
int DcdTensor::bins() const { return bins_; }

int DcdTensor::bin_of(double orientation_radians) const {
  if (!std::isfinite(orientation_radians)) {
    throw std::invalid_argument("DcdTensor::bin_of: the orientation is not finite");
  }
  const double folded = fold_orientation(orientation_radians);
  // Dividing by pi first keeps simple fractions exact (pi / 2 falls in bin bins / 2);
  // min() guards against rounding up to bins for a direction just below pi.
  return std::min(static_cast<int>(folded / M_PI * bins_), bins_ - 1);
}

void DcdTensor::check_bin(int bin) const {
  if (bin < 0 || bin >= bins_) {
    throw std::invalid_argument("DcdTensor: bin " + std::to_string(bin) + " outside 0.." +
                                std::to_string(bins_ - 1));
  }
}

float DcdTensor::at(int x, int y, int bin) const {
  check_bin(bin);
  if (x < 0 || x >= width() || y < 0 || y >= height()) {
    throw std::invalid_argument("DcdTensor: cell (" + std::to_string(x) + ", " +
                                std::to_string(y) + ") outside the tensor");
  }
  return layers_[bin].at<float>(y, x);
}

double DcdTensor::sample(double x, double y, int bin, double* dx, double* dy) const {
  check_bin(bin);
  const int w = width(), h = height();
  // Written so that NaN falls outside too.
  if (!(x >= 0.0 && x <= w - 1 && y >= 0.0 && y <= h - 1)) {
    if (dx) *dx = 0.0;
    if (dy) *dy = 0.0;
    if (!(std::abs(x) < 1e9 && std::abs(y) < 1e9)) return max_distance_;  // NaN, or far off
    return outside_cost(static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y)));
  }
  // The cell pair that brackets x; at the last centre, the pair that ends there.
  const int x0 = std::min(static_cast<int>(x), std::max(w - 2, 0));
  const int y0 = std::min(static_cast<int>(y), std::max(h - 2, 0));
  const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
  const double fx = x - x0, fy = y - y0;
  const cv::Mat& layer = layers_[bin];
  const double v00 = layer.at<float>(y0, x0), v10 = layer.at<float>(y0, x1);
  const double v01 = layer.at<float>(y1, x0), v11 = layer.at<float>(y1, x1);
  if (dx) *dx = (1.0 - fy) * (v10 - v00) + fy * (v11 - v01);
  if (dy) *dy = (1.0 - fx) * (v01 - v00) + fx * (v11 - v10);
  return (1.0 - fy) * ((1.0 - fx) * v00 + fx * v10) + fy * ((1.0 - fx) * v01 + fx * v11);
}

void DcdTensor::cap(const cv::Mat& mask, cv::Point mask_origin, float value) {
  if (mask.type() != CV_8UC1) throw std::invalid_argument("DcdTensor::cap: the mask must be 8-bit");
  hidden_ = mask.clone();
  hidden_origin_ = mask_origin;
  hidden_cost_ = std::min(value, max_distance_);
  // The part of the mask over the tensor caps its cells.
  const cv::Rect over_tensor = cv::Rect(mask_origin, mask.size()) & cv::Rect(0, 0, width(), height());
  if (over_tensor.empty()) return;
  const cv::Mat under = mask(over_tensor - mask_origin);
  for (cv::Mat& layer : layers_) {
    cv::Mat cells = layer(over_tensor), capped;
    cv::min(cells, hidden_cost_, capped);
    capped.copyTo(cells, under);
  }
}

float DcdTensor::outside_cost(int x, int y) const {
  const int mx = x - hidden_origin_.x, my = y - hidden_origin_.y;
  if (hidden_.empty() || mx < 0 || my < 0 || mx >= hidden_.cols || my >= hidden_.rows) return max_distance_;
  return hidden_.at<std::uint8_t>(my, mx) ? hidden_cost_ : max_distance_;
}

const cv::Mat& DcdTensor::layer(int bin) const {
  check_bin(bin);
  return layers_[bin];
}

}  // namespace flexsight

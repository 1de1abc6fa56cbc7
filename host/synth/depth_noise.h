#pragma once
// The depth a stereo camera would measure instead of the renderer's exact depth, so
// that the pose estimator is tuned and scored on depth as noisy as the product's: each
// pixel's disparity d = f B / z gets Gaussian noise of `disparity_sigma` pixels, and
// pixels within `edge_dropout` pixels of a depth discontinuity (where one camera sees
// what the other does not, and matching fails) have no depth. Depth noise therefore
// grows with z^2 / (f B), as it does for our matcher.
#include <cstdint>
#include <opencv2/core.hpp>

namespace flexsight {

struct StereoDepthNoise {
  double disparity_sigma = 0.0;  // pixels; 0 = exact depth, no change at all
  double baseline_mm = 100.0;
  int edge_dropout = 2;          // pixels
  void check() const;            // InputError ("option --depth-...") when out of range
};

// `depth`: CV_32FC1 mm, 0 where no surface; `focal` in pixels. The noise is a function
// of (key, pixel) only.
void apply_stereo_depth_noise(cv::Mat& depth, double focal, const StereoDepthNoise& noise,
                              std::uint64_t key);

}  // namespace flexsight

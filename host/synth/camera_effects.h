#pragma once
// What a camera adds to a picture: a slight optical blur and sensor noise, applied to
// the whole composite so that the parts and the background share them.
#include <cstdint>
#include <opencv2/core.hpp>

namespace flexsight {

// Gaussian blur of `blur_sigma` pixels (none for 0), then zero-mean Gaussian noise of
// `noise_sigma` grey levels per channel value, rounded to whole levels, saturated to
// 0..255. The noise is a function of (noise_key, value index) only: the same bytes for
// the same key. `rgb` CV_8UC3, changed in place.
void apply_camera_effects(cv::Mat& rgb, double blur_sigma, double noise_sigma,
                          std::uint64_t noise_key);

}  // namespace flexsight

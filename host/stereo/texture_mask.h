#pragma once
// Which pixels have texture to match: the support window's intensity spread against a
// floor. Computed on the host for both paths (the schedule uploads its bytes), so they
// stay identical.
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace flexsight {

// `rgb8`: CV_8UC3. 1 where the standard deviation of the grey level (the mean of the
// three channels) over the `window` x `window` square around the pixel (clipped at the
// image's edges) is at least `min_spread` grey levels, else 0; row-major. Sums are
// whole numbers and the test is exact, so every machine gives the same bytes.
std::vector<std::uint8_t> textured_pixel_mask(const cv::Mat& rgb8, int window, float min_spread);

}  // namespace flexsight

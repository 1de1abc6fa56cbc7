#include "host/io/middlebury_v2.h"

#include <cmath>
#include <cstdint>

#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

// Both ground truth and masks are 8-bit gray; some copies store them as three equal
// channels, which we accept by keeping one of them.
cv::Mat read_gray8(const std::string& path, const char* what) {
  const cv::Mat image = io_detail::imread_unchanged(path);
  if (image.depth() != CV_8U) {
    throw InputError(path, "unsupported bit depth " + io_detail::depth_name(image.depth()) +
                               " for " + what + " (expected 8-bit)");
  }
  return io_detail::single_channel_of_gray(image, path);
}

}  // namespace

cv::Mat read_middlebury_v2_disparity(const std::string& path, double scale) {
  if (!(scale > 0) || !std::isfinite(scale)) {
    throw InputError(path,
                     "disparity scale must be a positive number, got " + std::to_string(scale));
  }
  const cv::Mat gray = read_gray8(path, "a Middlebury v2 disparity map");
  return io_detail::decode_scaled_disparity<std::uint8_t>(gray, scale);  // 0 = unknown
}

cv::Mat read_mask(const std::string& path) { return read_gray8(path, "a mask"); }

}  // namespace flexsight

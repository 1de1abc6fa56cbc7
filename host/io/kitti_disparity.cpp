#include "host/io/kitti_disparity.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "host/io/atomic_file.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

// KITTI maps are PNGs by definition; checking the signature gives a clearer message
// than the decoder for, say, a JPEG or a text file named .png.
void require_png_signature(const std::string& path) {
  static const char kSignature[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};
  char head[8] = {};
  std::ifstream in(path, std::ios::binary);
  in.read(head, sizeof head);
  if (in.gcount() != sizeof head || !std::equal(head, head + 8, kSignature)) {
    throw InputError(path, "is not a PNG file (KITTI disparity maps are 16-bit PNGs)");
  }
}

std::uint16_t encode_disparity(float d) {
  if (!std::isfinite(d) || d < 0) return 0;  // 0 = no disparity
  // Clamp before rounding so huge values cannot overflow; valid values never become
  // 0, which would turn them into "no data".
  const double scaled = std::min(static_cast<double>(d) * 256.0, 65535.0);
  return static_cast<std::uint16_t>(std::clamp(std::round(scaled), 1.0, 65535.0));
}

}  // namespace

cv::Mat read_kitti_disparity(const std::string& path) {
  io_detail::require_readable_file(path);
  require_png_signature(path);
  const cv::Mat png = io_detail::imread_unchanged(path);
  if (png.depth() != CV_16U || png.channels() != 1) {
    throw InputError(path, "is " + io_detail::describe(png) +
                               ", but a KITTI disparity map must be a single-channel "
                               "16-bit PNG");
  }
  return io_detail::decode_scaled_disparity<std::uint16_t>(png, 256.0);  // value / 256: exact
}

void write_kitti_disparity(const std::string& path, const cv::Mat& disparity) {
  if (disparity.empty() || disparity.type() != CV_32FC1) {
    const std::string got = disparity.empty() ? "an empty image" : io_detail::describe(disparity);
    throw InputError(path,
                     "cannot be written as a KITTI disparity map: expected CV_32FC1, got " + got);
  }
  cv::Mat png(disparity.size(), CV_16UC1);
  for (int y = 0; y < disparity.rows; ++y) {
    const float* src = disparity.ptr<float>(y);
    auto* dst = png.ptr<std::uint16_t>(y);
    for (int x = 0; x < disparity.cols; ++x) dst[x] = encode_disparity(src[x]);
  }

  // Encoded in memory as PNG whatever the file name says, since the format is fixed.
  std::vector<unsigned char> encoded;
  if (!cv::imencode(".png", png, encoded)) {
    throw InputError(path, "cannot be encoded as PNG");
  }
  write_atomically(path, [&](const std::string& tmp_path) {
    std::ofstream out(tmp_path, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, "cannot be opened for writing");
    out.write(reinterpret_cast<const char*>(encoded.data()), std::streamsize(encoded.size()));
    out.close();
    if (!out) throw InputError(path, "cannot be written (write error)");
  });
}

}  // namespace flexsight

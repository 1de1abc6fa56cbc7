#include "host/io/image_io.h"

#include <cstdint>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "host/io/atomic_file.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

using io_detail::depth_name;

// 16-bit -> 8-bit with round-to-nearest: 65535 maps to 255 and 0 to 0. Done in integers
// so the result does not depend on floating-point rounding of v / 257.
cv::Mat to_8bit(const cv::Mat& image16) {
  cv::Mat image8(image16.size(), CV_MAKETYPE(CV_8U, image16.channels()));
  const int values_per_row = image16.cols * image16.channels();
  for (int y = 0; y < image16.rows; ++y) {
    const auto* src = image16.ptr<std::uint16_t>(y);
    auto* dst = image8.ptr<std::uint8_t>(y);
    for (int i = 0; i < values_per_row; ++i) {
      dst[i] = static_cast<std::uint8_t>((src[i] + 128u) / 257u);
    }
  }
  return image8;
}

// OpenCV decodes to BGR(A); the matcher works in RGB.
cv::Mat to_rgb(const cv::Mat& image8, const std::string& path) {
  cv::Mat rgb;
  switch (image8.channels()) {
    case 1:
      cv::cvtColor(image8, rgb, cv::COLOR_GRAY2RGB);
      break;
    case 3:
      cv::cvtColor(image8, rgb, cv::COLOR_BGR2RGB);
      break;
    case 4:  // alpha is dropped
      cv::cvtColor(image8, rgb, cv::COLOR_BGRA2RGB);
      break;
    default:
      throw InputError(
          path, "has " + std::to_string(image8.channels()) + " channels (expected 1, 3 or 4)");
  }
  return rgb;
}

// The inverse of to_rgb for writing: cv::imwrite expects BGR(A).
cv::Mat to_bgr_for_writing(const cv::Mat& image, const std::string& path) {
  cv::Mat bgr;
  switch (image.channels()) {
    case 1:
      return image;
    case 3:
      cv::cvtColor(image, bgr, cv::COLOR_RGB2BGR);
      return bgr;
    case 4:
      cv::cvtColor(image, bgr, cv::COLOR_RGBA2BGRA);
      return bgr;
    default:
      throw InputError(path, "cannot be written: image has " + std::to_string(image.channels()) +
                                 " channels (expected 1, 3 or 4)");
  }
}

}  // namespace

cv::Mat load_rgb8(const std::string& path) {
  cv::Mat image = io_detail::imread_unchanged(path);
  if (image.depth() == CV_16U) {
    image = to_8bit(image);
  } else if (image.depth() != CV_8U) {
    throw InputError(
        path, "unsupported bit depth " + depth_name(image.depth()) + " (expected 8- or 16-bit)");
  }
  return to_rgb(image, path);
}

StereoPair load_stereo_pair(const std::string& left_path, const std::string& right_path) {
  StereoPair pair;
  pair.left = load_rgb8(left_path);
  pair.right = load_rgb8(right_path);
  if (pair.left.size() != pair.right.size()) {
    throw InputError(right_path, "is " + io_detail::size_text(pair.right.size()) +
                                     " but the left image " + left_path + " is " +
                                     io_detail::size_text(pair.left.size()) +
                                     " (a stereo pair must have equal sizes)");
  }
  return pair;
}

void write_image(const std::string& path, const cv::Mat& image_rgb) {
  if (image_rgb.empty()) throw InputError(path, "cannot be written: the image is empty");
  if (image_rgb.depth() != CV_8U && image_rgb.depth() != CV_16U) {
    throw InputError(path, "cannot be written: unsupported bit depth " +
                               depth_name(image_rgb.depth()) + " (expected 8- or 16-bit)");
  }
  // Checked up front so the user reads this rather than OpenCV's exception text.
  if (!cv::haveImageWriter(path)) {
    throw InputError(path, "cannot be written: no image encoder for the extension '" +
                               std::filesystem::path(path).extension().string() + "'");
  }
  const cv::Mat bgr = to_bgr_for_writing(image_rgb, path);

  write_atomically(path, [&](const std::string& tmp_path) {
    bool written = false;
    try {
      written = cv::imwrite(tmp_path, bgr);
    } catch (const cv::Exception& e) {
      throw InputError(path, "cannot be encoded (" + e.err + ")");
    }
    if (!written) {
      throw InputError(path, "cannot be written (encoder failed or folder not writable)");
    }
  });
}

}  // namespace flexsight

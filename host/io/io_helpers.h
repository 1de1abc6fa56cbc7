#pragma once
// Internal helpers shared by the readers in host/io (not part of the public API).
// Header-only so that the list of sources in CMakeLists.txt stays as it is.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <system_error>

#include "host/io/input_error.h"
#include "host/io/png_structure.h"

namespace flexsight::io_detail {

// IEEE float as 4 little-endian bytes, whatever the host's byte order (PFM, PLY).
inline void encode_float_le(float value, char* out) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  for (int i = 0; i < 4; ++i) out[i] = static_cast<char>((bits >> (8 * i)) & 0xFFu);
}

// Checks the problems every reader shares before it looks at the content, so the
// user gets "does not exist" rather than a decoder's vague complaint.
inline void require_readable_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) {
    throw InputError(path, "cannot be accessed (" + ec.message() + ")");
  }
  if (!fs::exists(status)) throw InputError(path, "does not exist");
  if (fs::is_directory(status)) throw InputError(path, "is a directory, not a file");
  const auto size = fs::file_size(path, ec);
  if (!ec && size == 0) throw InputError(path, "is empty");
  std::ifstream probe(path, std::ios::binary);
  if (!probe) throw InputError(path, "cannot be opened");
}

// Whole file as bytes; the formats we parse by hand (PFM, calibration) are small
// enough that reading them at once keeps the parsers simple.
inline std::string read_whole_file(const std::string& path) {
  require_readable_file(path);
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path, "cannot be read");
  if (bytes.empty()) throw InputError(path, "is empty");
  return bytes;
}

// "8U", "16U", "32F", ... as users see them in OpenCV messages.
inline std::string depth_name(int depth) {
  switch (depth) {
    case CV_8U:
      return "8U";
    case CV_8S:
      return "8S";
    case CV_16U:
      return "16U";
    case CV_16S:
      return "16S";
    case CV_32S:
      return "32S";
    case CV_32F:
      return "32F";
    case CV_64F:
      return "64F";
    case CV_16F:
      return "16F";
    default:
      return "depth " + std::to_string(depth);
  }
}

// "16U 3-channel 640x480", for messages about an image we did not expect.
inline std::string describe(const cv::Mat& image) {
  return depth_name(image.depth()) + " " + std::to_string(image.channels()) + "-channel " +
         std::to_string(image.cols) + "x" + std::to_string(image.rows);
}

inline std::string size_text(const cv::Size& size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

// The image at `path` decoded as cv::imread with IMREAD_UNCHANGED would (keeps 16-bit
// and alpha), with the file checks above, a PNG's chunks checked first (png_structure.h)
// and OpenCV's exceptions turned into InputError. The file is read once: the check and
// the decoder share its bytes.
inline cv::Mat imread_unchanged(const std::string& path) {
  require_readable_file(path);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw InputError(path, "cannot be read");
  check_png_structure(path, bytes);
  cv::Mat image;
  try {
    const cv::Mat buffer(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data()));
    if (!bytes.empty()) image = cv::imdecode(buffer, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw InputError(path, "cannot be decoded as an image (" + e.err + ")");
  }
  if (image.empty()) throw InputError(path, "cannot be decoded as an image");
  return image;
}

// Some copies of gray maps (disparities, masks) are stored as three equal channels.
// Returns the single-channel view of `image`, or throws when the channels differ.
inline cv::Mat single_channel_of_gray(const cv::Mat& image, const std::string& path) {
  if (image.channels() == 1) return image;
  if (image.channels() != 3) {
    throw InputError(path, "has " + std::to_string(image.channels()) +
                               " channels (expected gray, or three equal channels)");
  }
  cv::Mat planes[3];
  cv::split(image, planes);
  if (cv::countNonZero(planes[0] != planes[1]) != 0 ||
      cv::countNonZero(planes[0] != planes[2]) != 0) {
    throw InputError(path, "is a color image (its three channels differ), expected gray");
  }
  return planes[0];
}

// The CV_32FC1 disparity map of an integer image of type T that holds disparity * scale,
// with +inf where it holds 0 (no disparity).
template <typename T>
cv::Mat decode_scaled_disparity(const cv::Mat& encoded, double scale) {
  cv::Mat disparity(encoded.size(), CV_32FC1);
  const float inf = std::numeric_limits<float>::infinity();
  for (int y = 0; y < encoded.rows; ++y) {
    const T* src = encoded.ptr<T>(y);
    float* dst = disparity.ptr<float>(y);
    for (int x = 0; x < encoded.cols; ++x) {
      dst[x] = src[x] == 0 ? inf : static_cast<float>(src[x] / scale);
    }
  }
  return disparity;
}

}  // namespace flexsight::io_detail

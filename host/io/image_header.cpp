#include "host/io/image_header.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

std::uint32_t big_endian(const unsigned char* bytes, int count) {
  std::uint32_t value = 0;
  for (int i = 0; i < count; ++i) value = (value << 8) | bytes[i];
  return value;
}

cv::Size checked_size(const std::string& path, std::uint32_t width, std::uint32_t height) {
  if (width == 0 || height == 0 || width > 0x7fffffffu || height > 0x7fffffffu) {
    throw InputError(path, "has an image size of " + std::to_string(width) + "x" + std::to_string(height) +
                               " in its header");
  }
  return {static_cast<int>(width), static_cast<int>(height)};
}

// PNG: signature, then the IHDR chunk (length, "IHDR", width, height, ...).
cv::Size png_size(const std::string& path, const std::vector<unsigned char>& head) {
  if (head.size() < 24 || std::memcmp(head.data() + 12, "IHDR", 4) != 0) {
    throw InputError(path, "is not a valid PNG: it does not start with an IHDR chunk");
  }
  return checked_size(path, big_endian(head.data() + 16, 4), big_endian(head.data() + 20, 4));
}

// JPEG: segments after SOI until a start-of-frame marker (SOF0..SOF15 but DHT C4, JPG C8
// and DAC CC), whose payload is precision, height, width.
cv::Size jpeg_size(const std::string& path, std::ifstream& in) {
  in.seekg(2);
  unsigned char marker[4];
  while (in.read(reinterpret_cast<char*>(marker), 4)) {
    if (marker[0] != 0xff) break;
    const unsigned char type = marker[1];
    const std::uint32_t length = big_endian(marker + 2, 2);
    if (length < 2) break;
    const bool frame = type >= 0xc0 && type <= 0xcf && type != 0xc4 && type != 0xc8 && type != 0xcc;
    if (frame) {
      unsigned char header[5];
      if (!in.read(reinterpret_cast<char*>(header), 5)) break;
      return checked_size(path, big_endian(header + 3, 2), big_endian(header + 1, 2));
    }
    in.seekg(length - 2, std::ios::cur);
  }
  // An unusual layout (fill bytes, a cut file): the decoder has the last word.
  return io_detail::imread_unchanged(path).size();
}

}  // namespace

cv::Size image_size_from_header(const std::string& path) {
  io_detail::require_readable_file(path);
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> head(24);
  in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  in.clear();
  if (head.size() >= 8 && std::memcmp(head.data(), kPngSignature, 8) == 0) return png_size(path, head);
  if (head.size() >= 3 && head[0] == 0xff && head[1] == 0xd8 && head[2] == 0xff) return jpeg_size(path, in);
  return io_detail::imread_unchanged(path).size();
}

}  // namespace flexsight

#include "host/io/png_structure.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <zlib.h>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

// zlib's CRC-32 is the one the PNG specification defines (ISO 3309).
std::uint32_t png_crc(const unsigned char* bytes, std::size_t size) {
  return static_cast<std::uint32_t>(::crc32(0L, bytes, static_cast<uInt>(size)));
}

std::uint32_t big_endian(const unsigned char* bytes) {
  return (std::uint32_t{bytes[0]} << 24) | (std::uint32_t{bytes[1]} << 16) | (std::uint32_t{bytes[2]} << 8) |
         std::uint32_t{bytes[3]};
}

}  // namespace

void check_png_structure(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  check_png_structure(path, std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
}

void check_png_structure(const std::string& path, const std::string& file) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(file.data());
  if (file.size() < sizeof kSignature || std::memcmp(bytes, kSignature, sizeof kSignature) != 0) return;
  std::size_t pos = sizeof kSignature;
  bool first = true;
  while (pos < file.size()) {
    const std::string at = " at byte " + std::to_string(pos);
    if (file.size() - pos < 12) {
      throw InputError(path, "is a truncated PNG: the chunk" + at + " runs past the end of the file (" +
                                 std::to_string(file.size()) + " bytes)");
    }
    const std::uint32_t length = big_endian(bytes + pos);
    const std::string type(file, pos + 4, 4);
    if (length > file.size() - pos - 12) {
      throw InputError(path, "is a truncated PNG: its " + type + " chunk" + at + " runs past the end of the file (" +
                                 std::to_string(file.size()) + " bytes)");
    }
    if (first && type != "IHDR") throw InputError(path, "is not a valid PNG: its first chunk is not IHDR");
    if (png_crc(bytes + pos + 4, length + 4) != big_endian(bytes + pos + 8 + length)) {
      throw InputError(path, "is a damaged PNG: the CRC of its " + type + " chunk" + at + " does not match its bytes");
    }
    if (type == "IEND") return;
    pos += 12 + length;
    first = false;
  }
  throw InputError(path, "is a truncated PNG: it ends before its IEND chunk");
}

}  // namespace flexsight

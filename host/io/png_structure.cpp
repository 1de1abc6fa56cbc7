#include "host/io/png_structure.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

// CRC-32 as the PNG specification defines it (ISO 3309, polynomial 0xedb88320).
std::uint32_t crc32(const unsigned char* bytes, std::size_t size) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xffffffffu;
  for (std::size_t i = 0; i < size; ++i) c = table[(c ^ bytes[i]) & 0xffu] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

std::uint32_t big_endian(const unsigned char* bytes) {
  return (std::uint32_t{bytes[0]} << 24) | (std::uint32_t{bytes[1]} << 16) | (std::uint32_t{bytes[2]} << 8) |
         std::uint32_t{bytes[3]};
}

}  // namespace

void check_png_structure(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
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
    if (crc32(bytes + pos + 4, length + 4) != big_endian(bytes + pos + 8 + length)) {
      throw InputError(path, "is a damaged PNG: the CRC of its " + type + " chunk" + at + " does not match its bytes");
    }
    if (type == "IEND") return;
    pos += 12 + length;
    first = false;
  }
  throw InputError(path, "is a truncated PNG: it ends before its IEND chunk");
}

}  // namespace flexsight

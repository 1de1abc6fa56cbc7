#pragma once
// What the STL, PLY and OBJ readers (mesh_stl.cpp, mesh_ply.cpp, mesh_obj.cpp) share:
// their messages, whitespace tokens, whole-token numbers and little-endian values. Internal
// to host/render; the readers' API is mesh_files.h.
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace flexsight::mesh_files::detail {

// Throws InputError(path, problem).
[[noreturn]] void fail(const std::string& path, const std::string& problem);

// A token of the file as a message may show it: printable, at most 24 characters.
std::string shown(std::string_view token);

inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

// The whitespace-separated words of one line, in `words` (cleared first).
void split_words(std::string_view line, std::vector<std::string_view>& words);

// A whole token as a number of type T ('+' allowed in front, as C's strtod does).
template <typename T>
bool parse_number(std::string_view s, T& value) {
  if (!s.empty() && s[0] == '+') {
    s.remove_prefix(1);
    if (!s.empty() && s[0] == '-') return false;
  }
  if (s.empty()) return false;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), value);
  return error == std::errc() && end == s.data() + s.size();
}

// Whitespace-separated tokens of bytes[start, end), with the line each is on.
class Tokens {
 public:
  Tokens(const std::string& bytes, size_t start, size_t line) : bytes_(bytes), pos_(start), line_(line) {}

  bool next(std::string_view& token) {
    while (pos_ < bytes_.size() && is_space(bytes_[pos_])) {
      if (bytes_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ == bytes_.size()) return false;
    const size_t begin = pos_;
    while (pos_ < bytes_.size() && !is_space(bytes_[pos_])) ++pos_;
    token = std::string_view(bytes_).substr(begin, pos_ - begin);
    return true;
  }
  // Skips what is left of the current line (an STL solid's name).
  void skip_line() {
    while (pos_ < bytes_.size() && bytes_[pos_] != '\n') ++pos_;
  }
  size_t line() const { return line_; }
  size_t left() const { return bytes_.size() - pos_; }

 private:
  const std::string& bytes_;
  size_t pos_;
  size_t line_;
};

inline std::uint32_t little_u32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
         std::uint32_t(b[3]) << 24;
}

inline float little_float(const char* p) {
  const std::uint32_t bits = little_u32(p);
  float value;
  std::memcpy(&value, &bits, 4);
  return value;
}

// `count` as the index of the next vertex; refused when 32 bits cannot hold it.
inline std::uint32_t checked_index(const std::string& path, size_t count) {
  if (count >= std::numeric_limits<std::uint32_t>::max()) fail(path, "has more than 2^32 vertices");
  return std::uint32_t(count);
}

}  // namespace flexsight::mesh_files::detail

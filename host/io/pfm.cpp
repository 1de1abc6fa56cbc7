#include "host/io/pfm.h"

#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "host/io/atomic_file.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

// The three header lines of a PFM file, exactly as the format defines them: the magic,
// "width height", the scale; each ends with '\n' (a '\r' before it is allowed for files
// written in text mode on Windows), and the data starts right after the third. No
// comments, no tokens moved to another line: a header that says something else is not
// read as something it is not.
class HeaderLines {
 public:
  HeaderLines(const std::string& bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  // The whitespace-separated fields of the next line; InputError naming `what` when the
  // file ends first or the line is longer than any header line can be.
  std::vector<std::string> next_line(const char* what) {
    const std::size_t end = bytes_.find('\n', pos_);
    if (end == std::string::npos || end - pos_ > kMaxLine) {
      throw InputError(path_, std::string("header ends before the end of its ") + what + " line");
    }
    std::string line = bytes_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos_ = end + 1;
    std::vector<std::string> fields;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      const std::size_t start = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
      if (i > start) fields.push_back(line.substr(start, i - start));
    }
    return fields;
  }
  std::size_t data_offset() const { return pos_; }

 private:
  static constexpr std::size_t kMaxLine = 128;
  const std::string& bytes_;
  const std::string& path_;
  std::size_t pos_ = 0;
};

// Shows a token from a possibly binary file in a message without control characters.
std::string printable(const std::string& token) {
  std::string out;
  for (char c : token.substr(0, 16)) {
    out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  }
  return out;
}

long long parse_dimension(const std::string& token, const char* what, const std::string& path) {
  long long value = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec != std::errc() || ptr != end) {
    throw InputError(
        path, std::string("has a malformed ") + what + " '" + printable(token) + "' in its header");
  }
  return value;
}

double parse_scale(const std::string& token, const std::string& path) {
  double value = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) {
    throw InputError(path, "has a malformed scale '" + printable(token) + "' in its header");
  }
  if (value == 0.0) {
    throw InputError(path, "has a zero scale (its sign must give the byte order)");
  }
  return value;
}

// Decoding through an integer makes the result independent of the host's byte order.
float decode_float(const unsigned char* b, bool little_endian) {
  const std::uint32_t bits = little_endian
                                 ? std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 |
                                       std::uint32_t{b[2]} << 16 | std::uint32_t{b[3]} << 24
                                 : std::uint32_t{b[3]} | std::uint32_t{b[2]} << 8 |
                                       std::uint32_t{b[1]} << 16 | std::uint32_t{b[0]} << 24;
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

struct PfmHeader {
  int width = 0;
  int height = 0;
  int channels = 0;
  bool little_endian = true;
  std::size_t data_offset = 0;
};

PfmHeader parse_header(const std::string& bytes, const std::string& path) {
  HeaderLines lines(bytes, path);
  PfmHeader header;

  const std::vector<std::string> magic = lines.next_line("magic");
  const std::string magic_text = magic.empty() ? std::string() : magic[0];
  if (magic.size() == 1 && magic_text == "Pf") {
    header.channels = 1;
  } else if (magic.size() == 1 && magic_text == "PF") {
    header.channels = 3;
  } else {
    throw InputError(path, "is not a PFM file (first line '" + printable(bytes.substr(0, bytes.find('\n'))) +
                               "', expected 'Pf' or 'PF')");
  }

  const std::vector<std::string> size = lines.next_line("size");
  if (size.size() != 2) {
    throw InputError(path, "has " + std::to_string(size.size()) +
                               " fields on its size line, expected two: width height");
  }
  const long long width = parse_dimension(size[0], "width", path);
  const long long height = parse_dimension(size[1], "height", path);
  if (width <= 0 || height <= 0) {
    throw InputError(path, "has non-positive dimensions " + std::to_string(width) + "x" +
                               std::to_string(height) + " in its header");
  }
  if (width > INT_MAX || height > INT_MAX) {
    throw InputError(path, "has implausibly large dimensions " + std::to_string(width) + "x" +
                               std::to_string(height) + " in its header");
  }
  header.width = static_cast<int>(width);
  header.height = static_cast<int>(height);

  const std::vector<std::string> scale = lines.next_line("scale");
  if (scale.size() != 1) {
    throw InputError(path, "has " + std::to_string(scale.size()) +
                               " fields on its scale line, expected one number");
  }
  header.little_endian = parse_scale(scale[0], path) < 0;
  header.data_offset = lines.data_offset();
  return header;
}

// Throws unless `available` bytes hold the whole image. Written so that the
// multiplication cannot overflow for any dimensions that passed parse_header.
void check_data_length(const PfmHeader& header, std::size_t available, const std::string& path) {
  const std::uint64_t row_bytes = std::uint64_t(header.width) * header.channels * 4;
  const std::uint64_t rows = std::uint64_t(header.height);
  const bool enough = rows <= available / row_bytes;
  if (enough) return;
  const std::string needed = rows <= std::numeric_limits<std::uint64_t>::max() / row_bytes
                                 ? std::to_string(rows * row_bytes)
                                 : "too many";
  throw InputError(path, "header says " + std::to_string(header.width) + "x" +
                             std::to_string(header.height) + "x" + std::to_string(header.channels) +
                             " (" + needed + " bytes) but only " + std::to_string(available) +
                             " bytes of data follow");
}

}  // namespace

cv::Mat read_pfm(const std::string& path) {
  const std::string bytes = io_detail::read_whole_file(path);
  PfmHeader header = parse_header(bytes, path);

  check_data_length(header, bytes.size() - header.data_offset, path);
  // Bytes after the last row mean the header describes another file than this one.
  const std::size_t needed =
      std::size_t(header.width) * std::size_t(header.height) * header.channels * 4;
  if (bytes.size() - header.data_offset != needed) {
    throw InputError(path, "has " + std::to_string(bytes.size() - header.data_offset - needed) +
                               " bytes after the " + std::to_string(header.width) + "x" +
                               std::to_string(header.height) + "x" + std::to_string(header.channels) +
                               " image its header describes");
  }

  cv::Mat image(header.height, header.width, CV_MAKETYPE(CV_32F, header.channels));
  const int values_per_row = header.width * header.channels;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data()) + header.data_offset;
  for (int file_row = 0; file_row < header.height; ++file_row) {
    // PFM stores the bottom row first.
    auto* dst = image.ptr<float>(header.height - 1 - file_row);
    const unsigned char* src = data + std::size_t(file_row) * values_per_row * 4;
    for (int i = 0; i < values_per_row; ++i) {
      dst[i] = decode_float(src + 4 * i, header.little_endian);
    }
  }
  return image;
}

void write_pfm(const std::string& path, const cv::Mat& image) {
  if (image.empty() || (image.type() != CV_32FC1 && image.type() != CV_32FC3)) {
    const std::string got = image.empty() ? "an empty image" : io_detail::describe(image);
    throw InputError(path, "cannot be written as PFM: expected CV_32FC1 or CV_32FC3, got " + got);
  }
  const std::string header = std::string(image.channels() == 1 ? "Pf" : "PF") + "\n" +
                             std::to_string(image.cols) + " " + std::to_string(image.rows) +
                             "\n-1\n";  // negative scale: little-endian data

  const int values_per_row = image.cols * image.channels();
  std::string row_bytes(std::size_t(values_per_row) * 4, '\0');
  write_atomically(path, [&](const std::string& tmp_path) {
    std::ofstream out(tmp_path, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, "cannot be opened for writing");
    out.write(header.data(), std::streamsize(header.size()));
    for (int y = image.rows - 1; y >= 0; --y) {  // bottom row first
      const float* src = image.ptr<float>(y);
      for (int i = 0; i < values_per_row; ++i) io_detail::encode_float_le(src[i], &row_bytes[4 * i]);
      out.write(row_bytes.data(), std::streamsize(row_bytes.size()));
    }
    out.close();
    if (!out) throw InputError(path, "cannot be written (write error)");
  });
}

}  // namespace flexsight

#include "host/dataset/coco_rle.h"

#include <limits>

#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {

CocoRle rle_encode(const cv::Mat& mask) {
  if (mask.type() != CV_8UC1) {
    throw InputError("rle", "mask is " + io_detail::describe(mask) + ", expected 8U gray");
  }
  CocoRle rle;
  rle.height = mask.rows;
  rle.width = mask.cols;
  bool previous = false;  // the first run counts zeros
  std::uint32_t run = 0;
  for (int x = 0; x < mask.cols; ++x) {
    for (int y = 0; y < mask.rows; ++y) {
      const bool set = mask.at<uchar>(y, x) != 0;
      if (set != previous) {
        rle.counts.push_back(run);
        run = 0;
        previous = set;
      }
      ++run;
    }
  }
  rle.counts.push_back(run);
  return rle;
}

cv::Mat rle_decode(const CocoRle& rle) {
  std::uint64_t total = 0;
  for (std::uint32_t count : rle.counts) total += count;
  const std::uint64_t pixels = static_cast<std::uint64_t>(rle.height) * rle.width;
  if (rle.height < 0 || rle.width < 0 || total != pixels) {
    throw InputError("rle", "counts sum to " + std::to_string(total) + " but the mask has " +
                                std::to_string(rle.height) + "x" + std::to_string(rle.width) +
                                " pixels");
  }
  cv::Mat mask(rle.height, rle.width, CV_8UC1, cv::Scalar(0));
  std::uint64_t position = 0;  // column-major index of the next pixel
  for (std::size_t i = 0; i < rle.counts.size(); ++i) {
    const std::uint64_t end = position + rle.counts[i];
    if (i % 2 == 1) {
      for (std::uint64_t p = position; p < end; ++p) {
        mask.at<uchar>(static_cast<int>(p % rle.height), static_cast<int>(p / rle.height)) = 255;
      }
    }
    position = end;
  }
  return mask;
}

std::uint64_t rle_area(const CocoRle& rle) {
  std::uint64_t area = 0;
  for (std::size_t i = 1; i < rle.counts.size(); i += 2) area += rle.counts[i];
  return area;
}

cv::Rect rle_box(const CocoRle& rle) {
  if (rle.height <= 0) return {};
  std::uint64_t position = 0;
  long long x_min = std::numeric_limits<long long>::max(), y_min = x_min;
  long long x_max = -1, y_max = -1;
  for (std::size_t i = 0; i < rle.counts.size(); ++i) {
    const std::uint64_t start = position;
    position += rle.counts[i];
    if (i % 2 == 0 || rle.counts[i] == 0) continue;
    const std::uint64_t last = position - 1;
    const long long x0 = start / rle.height, x1 = last / rle.height;
    // A run that continues into the next column covers the last row of one column and
    // the first row of the next: the box then spans every row.
    const long long y0 = x0 == x1 ? start % rle.height : 0;
    const long long y1 = x0 == x1 ? last % rle.height : rle.height - 1;
    x_min = std::min(x_min, x0);
    x_max = std::max(x_max, x1);
    y_min = std::min(y_min, y0);
    y_max = std::max(y_max, y1);
  }
  if (x_max < 0) return {};
  return cv::Rect(static_cast<int>(x_min), static_cast<int>(y_min),
                  static_cast<int>(x_max - x_min + 1), static_cast<int>(y_max - y_min + 1));
}

std::string rle_counts_to_string(const std::vector<std::uint32_t>& counts) {
  std::string text;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    long long x = counts[i];
    if (i > 2) x -= counts[i - 2];
    bool more = true;
    while (more) {
      int c = static_cast<int>(x & 0x1f);
      x >>= 5;  // arithmetic shift: a negative difference ends at -1
      more = (c & 0x10) ? x != -1 : x != 0;
      if (more) c |= 0x20;
      text.push_back(static_cast<char>(c + 48));
    }
  }
  return text;
}

std::vector<std::uint32_t> rle_counts_from_string(const std::string& text,
                                                  const std::string& subject) {
  std::vector<std::uint32_t> counts;
  std::size_t p = 0;
  while (p < text.size()) {
    long long x = 0;
    int k = 0;
    bool more = true;
    while (more) {
      if (p >= text.size()) {
        throw InputError(subject, "RLE counts string ends inside a count");
      }
      const int c = static_cast<unsigned char>(text[p]) - 48;
      if (c < 0 || c > 63) {
        throw InputError(subject, "RLE counts string has the character '" +
                                      std::string(1, text[p]) + "' (expected '0'..'o')");
      }
      if (k > 7) throw InputError(subject, "RLE counts string has a count too long");
      x |= static_cast<long long>(c & 0x1f) << (5 * k);
      more = (c & 0x20) != 0;
      ++p;
      ++k;
      if (!more && (c & 0x10)) x |= -1LL * (1LL << (5 * k));  // sign extension
    }
    if (counts.size() > 2) x += counts[counts.size() - 2];
    if (x < 0 || x > std::numeric_limits<std::uint32_t>::max()) {
      throw InputError(subject, "RLE count " + std::to_string(counts.size()) + " decodes to " +
                                    std::to_string(x) + " (out of range)");
    }
    counts.push_back(static_cast<std::uint32_t>(x));
  }
  return counts;
}

}  // namespace flexsight

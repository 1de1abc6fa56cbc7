#include "fallback/stereo/texture_mask.h"

#include <algorithm>
#include <stdexcept>

namespace flexsight {

std::vector<std::uint8_t> textured_pixel_mask(const cv::Mat& rgb8, int window, float min_spread) {
  if (rgb8.type() != CV_8UC3 || rgb8.empty() || window < 1) {
    throw std::invalid_argument("textured_pixel_mask: a CV_8UC3 image and a window of at least 1");
  }
  const int width = rgb8.cols, height = rgb8.rows, radius = window / 2;
  // Integral images of g = r + g + b (three times the grey level) and of g^2, exact in
  // 64-bit integers (at most 765^2 per pixel).
  std::vector<std::int64_t> sum(static_cast<size_t>(width + 1) * (height + 1), 0);
  std::vector<std::int64_t> square(sum.size(), 0);
  for (int y = 0; y < height; ++y) {
    const cv::Vec3b* row = rgb8.ptr<cv::Vec3b>(y);
    std::int64_t row_sum = 0, row_square = 0;
    for (int x = 0; x < width; ++x) {
      const std::int64_t g = static_cast<std::int64_t>(row[x][0]) + row[x][1] + row[x][2];
      row_sum += g;
      row_square += g * g;
      const size_t at = static_cast<size_t>(y + 1) * (width + 1) + (x + 1);
      sum[at] = sum[at - (width + 1)] + row_sum;
      square[at] = square[at - (width + 1)] + row_square;
    }
  }
  // spread >= min_spread  <=>  n * S2 - S1^2 >= (3 min_spread)^2 n^2, with n the count.
  const double floor_squared = 9.0 * static_cast<double>(min_spread) * min_spread;
  std::vector<std::uint8_t> mask(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    const int y0 = std::max(0, y - radius), y1 = std::min(height, y + radius + 1);
    for (int x = 0; x < width; ++x) {
      const int x0 = std::max(0, x - radius), x1 = std::min(width, x + radius + 1);
      auto box = [&](const std::vector<std::int64_t>& table) {
        return table[static_cast<size_t>(y1) * (width + 1) + x1] - table[static_cast<size_t>(y0) * (width + 1) + x1] -
               table[static_cast<size_t>(y1) * (width + 1) + x0] + table[static_cast<size_t>(y0) * (width + 1) + x0];
      };
      const std::int64_t n = static_cast<std::int64_t>(y1 - y0) * (x1 - x0);
      const std::int64_t s1 = box(sum);
      const std::int64_t scatter = n * box(square) - s1 * s1;  // n^2 times the variance of g
      mask[static_cast<size_t>(y) * width + x] =
          static_cast<double>(scatter) >= floor_squared * static_cast<double>(n) * static_cast<double>(n) ? 1 : 0;
    }
  }
  return mask;
}

}  // namespace flexsight

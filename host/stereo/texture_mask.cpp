#include "host/stereo/texture_mask.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace flexsight {

std::vector<std::uint8_t> textured_pixel_mask(const cv::Mat& rgb8, int window, float min_spread) {
  if (rgb8.type() != CV_8UC3 || rgb8.empty() || window < 1) {
    throw std::invalid_argument("textured_pixel_mask: a CV_8UC3 image and a window of at least 1");
  }
  const int width = rgb8.cols, height = rgb8.rows, radius = window / 2;
  // g = r + g + b, three times the grey level (at most 765), and OpenCV's integral images
  // of g and g^2 in doubles: whole numbers below 2^53 even at 12 MP, so exact.
  cv::Mat wide, g;
  rgb8.convertTo(wide, CV_16U);  // transform keeps the source's depth: 8 bits would saturate
  cv::transform(wide, g, cv::Matx13f(1.0f, 1.0f, 1.0f));
  cv::Mat sum, square;
  cv::integral(g, sum, square, CV_64F, CV_64F);
  auto box = [](const cv::Mat& table, int x0, int y0, int x1, int y1) {
    return table.at<double>(y1, x1) - table.at<double>(y0, x1) - table.at<double>(y1, x0) + table.at<double>(y0, x0);
  };
  // spread >= min_spread  <=>  n * S2 - S1^2 >= (3 min_spread)^2 n^2, with n the count.
  const double floor_squared = 9.0 * static_cast<double>(min_spread) * min_spread;
  std::vector<std::uint8_t> mask(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    const int y0 = std::max(0, y - radius), y1 = std::min(height, y + radius + 1);
    for (int x = 0; x < width; ++x) {
      const int x0 = std::max(0, x - radius), x1 = std::min(width, x + radius + 1);
      const double n = static_cast<double>(y1 - y0) * (x1 - x0);
      const double s1 = box(sum, x0, y0, x1, y1);
      const double scatter = n * box(square, x0, y0, x1, y1) - s1 * s1;  // n^2 times the variance of g
      mask[static_cast<size_t>(y) * width + x] = scatter >= floor_squared * n * n ? 1 : 0;
    }
  }
  return mask;
}

}  // namespace flexsight

#pragma once
// Small images written out row by row in a test, e.g. rows_to_mat({{1, 2, kInf}, {4, 5, 6}}):
// the hand-computed cases of the metric, report and dataset tests.
#include <cstdint>
#include <initializer_list>
#include <opencv2/core.hpp>

namespace flexsight::testing_support {

namespace detail {

template <typename Pixel, typename Value>
cv::Mat mat_from_rows(std::initializer_list<std::initializer_list<Value>> rows) {
  const int cols = static_cast<int>(rows.begin()->size());
  cv::Mat image(static_cast<int>(rows.size()), cols, cv::DataType<Pixel>::type);
  int y = 0;
  for (const auto& row : rows) {
    CV_Assert(static_cast<int>(row.size()) == cols);  // every row as long as the first
    int x = 0;
    for (Value value : row) image.at<Pixel>(y, x++) = static_cast<Pixel>(value);
    ++y;
  }
  return image;
}

}  // namespace detail

// CV_32FC1, e.g. a disparity map or ground truth.
inline cv::Mat rows_to_mat(std::initializer_list<std::initializer_list<float>> rows) {
  return detail::mat_from_rows<float>(rows);
}

// CV_8UC1, e.g. a non-occlusion mask (255 / 128 / 0) or a selection.
inline cv::Mat rows_to_mask(std::initializer_list<std::initializer_list<int>> rows) {
  return detail::mat_from_rows<std::uint8_t>(rows);
}

// CV_16UC1, e.g. a KITTI disparity PNG (disparity * 256, 0 = none).
inline cv::Mat rows_to_u16(std::initializer_list<std::initializer_list<int>> rows) {
  return detail::mat_from_rows<std::uint16_t>(rows);
}

}  // namespace flexsight::testing_support

// The edge thresholds' modes (host/pose/edge_thresholds.h) on images whose edges are
// known: a bright square on a dark ground, seen through a lower gain, and under noise.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "host/pose/dcd_tensor.h"
#include "host/pose/edge_thresholds.h"

namespace {

using flexsight::DcdParams;
using Mode = DcdParams::EdgeThresholds;

// 120 x 120 grey, a 60 x 60 square of `inside` on `outside`.
cv::Mat square(int outside, int inside) {
  cv::Mat image(120, 120, CV_8UC1, cv::Scalar(outside));
  image(cv::Rect(30, 30, 60, 60)).setTo(inside);
  return image;
}

cv::Mat with_noise(const cv::Mat& image, double sigma) {
  cv::Mat noise(image.size(), CV_32FC1);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  cv::Mat noisy;
  image.convertTo(noisy, CV_32FC1);
  noisy += noise;
  noisy.convertTo(noisy, CV_8UC1);
  return noisy;
}

struct EdgeCount {
  int on_square = 0;  // edge pixels within 2 px of the square's outline
  int elsewhere = 0;
};

EdgeCount count_edges(const cv::Mat& image, Mode mode) {
  DcdParams params;
  params.thresholds = mode;
  const flexsight::EdgeMap edges = flexsight::detect_edges(image, cv::Rect(0, 0, image.cols, image.rows), params);
  cv::Mat outline(image.size(), CV_8UC1, cv::Scalar(0));
  cv::rectangle(outline, cv::Rect(30, 30, 60, 60), cv::Scalar(255), 5);
  EdgeCount count;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      if (edges.mask.at<uchar>(y, x) == 0) continue;
      (outline.at<uchar>(y, x) ? count.on_square : count.elsewhere)++;
    }
  }
  return count;
}

TEST(EdgeThresholds, ContrastStretchFindsTheEdgesOfADimImage) {
  const EdgeCount bright = count_edges(square(40, 160), Mode::kFixed);
  ASSERT_GE(bright.on_square, 200);  // the outline is 4 x 60 pixels
  // A quarter of the gain: the step is 30 grey levels, below the fixed thresholds.
  const cv::Mat dim = square(10, 40);
  EXPECT_LT(count_edges(dim, Mode::kFixed).on_square, 20);
  const EdgeCount stretched = count_edges(dim, Mode::kContrast);
  EXPECT_GE(stretched.on_square, bright.on_square * 9 / 10);
  EXPECT_EQ(stretched.elsewhere, 0);
}

TEST(EdgeThresholds, NoiseFloorKeepsEdgesOutOfNoise) {
  const cv::Mat noisy = with_noise(square(40, 160), 25.0);
  const EdgeCount fixed = count_edges(noisy, Mode::kFixed);
  const EdgeCount floor = count_edges(noisy, Mode::kNoise);
  EXPECT_GT(fixed.elsewhere, 200);  // sigma 25 makes edges all over the flat ground
  EXPECT_LT(floor.elsewhere, fixed.elsewhere / 10);
  EXPECT_GE(floor.on_square, 150);
}

TEST(EdgeThresholds, CleanImagesKeepTheFixedThresholds) {
  // No noise: the measured noise is 0 and the thresholds stay as given.
  const cv::Mat clean = square(40, 160);
  cv::Mat dx, dy;
  cv::Sobel(clean, dx, CV_16S, 1, 0, 3);
  cv::Sobel(clean, dy, CV_16S, 0, 1, 3);
  const flexsight::CannyThresholds kept = flexsight::above_gradient_noise({40.0, 100.0}, dx, dy);
  EXPECT_EQ(kept.low, 40.0);
  EXPECT_EQ(kept.high, 100.0);
  EXPECT_EQ(count_edges(clean, Mode::kNoise).on_square, count_edges(clean, Mode::kFixed).on_square);
}

TEST(EdgeThresholds, StretchLeavesAFlatRegionAlone) {
  cv::Mat flat(20, 20, CV_8UC1, cv::Scalar(100));
  flat.at<uchar>(3, 3) = 104;
  const cv::Mat before = flat.clone();
  flexsight::stretch_contrast(flat);
  EXPECT_EQ(cv::countNonZero(flat != before), 0);
}

}  // namespace

// textured_pixel_mask (host/stereo/texture_mask.h): which pixels' windows have
// texture to match; the active preset's gate before the fill.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <stdexcept>

#include "host/stereo/texture_mask.h"

namespace flexsight {
namespace {

// Rows alternating between two grey levels.
cv::Mat striped_rows(int width, int height, int a, int b) {
  cv::Mat image(height, width, CV_8UC3);
  for (int y = 0; y < height; ++y) image.row(y).setTo(cv::Scalar::all(y % 2 ? b : a));
  return image;
}

// A 3x3 window inside rows of 10 and 14 holds 6 of one and 3 of the other: a standard
// deviation of 4 sqrt(2) / 3 = 1.8856 grey levels.
TEST(TextureMask, TheFloorIsTheWindowsStandardDeviation) {
  const cv::Mat image = striped_rows(12, 10, 10, 14);
  const auto below = textured_pixel_mask(image, 3, 1.885f);
  const auto above = textured_pixel_mask(image, 3, 1.886f);
  for (int y = 1; y < 9; ++y) {
    for (int x = 1; x < 11; ++x) {
      EXPECT_EQ(below[y * 12 + x], 1) << x << "," << y;
      EXPECT_EQ(above[y * 12 + x], 0) << x << "," << y;
    }
  }
}

// Flat grey left, another grey right: only the windows that reach across the edge see texture.
TEST(TextureMask, OnlyWindowsReachingAnEdgeAreTextured) {
  cv::Mat image(8, 20, CV_8UC3, cv::Scalar::all(40));
  image.colRange(10, 20).setTo(cv::Scalar::all(90));
  const auto mask = textured_pixel_mask(image, 5, 4.0f);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 20; ++x) {
      EXPECT_EQ(mask[y * 20 + x], (x >= 8 && x <= 11) ? 1 : 0) << x << "," << y;
    }
  }
}

// The grey level is the mean of the channels: colour that changes only the hue is no texture.
TEST(TextureMask, HueAloneIsNoTexture) {
  cv::Mat image(6, 6, CV_8UC3, cv::Scalar(30, 60, 90));
  image.colRange(3, 6).setTo(cv::Scalar(90, 60, 30));
  for (std::uint8_t m : textured_pixel_mask(image, 3, 0.5f)) EXPECT_EQ(m, 0);
  for (std::uint8_t m : textured_pixel_mask(image, 3, 0.0f)) EXPECT_EQ(m, 1) << "a floor of 0 keeps every pixel";
}

// Bright greys (channel sums of 600 and 750) are still told apart: the sum of the three
// channels must not saturate at 8 bits.
TEST(TextureMask, BrightGreysAreNotSaturated) {
  cv::Mat image(8, 20, CV_8UC3, cv::Scalar::all(200));
  image.colRange(10, 20).setTo(cv::Scalar::all(250));
  const auto mask = textured_pixel_mask(image, 5, 4.0f);
  EXPECT_EQ(mask[4 * 20 + 9], 1);
  EXPECT_EQ(mask[4 * 20 + 10], 1);
  EXPECT_EQ(mask[4 * 20 + 2], 0);
}

TEST(TextureMask, RefusesAnImageThatIsNotRgb8) {
  EXPECT_THROW(textured_pixel_mask(cv::Mat(4, 4, CV_8UC1, cv::Scalar(0)), 3, 1.0f), std::invalid_argument);
  EXPECT_THROW(textured_pixel_mask(cv::Mat(), 3, 1.0f), std::invalid_argument);
}

}  // namespace
}  // namespace flexsight

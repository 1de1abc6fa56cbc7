// Image preparation: integer-exact downsampling, gradients, level counts.
#include <gtest/gtest.h>

#include "fallback/stereo/image_pyramid.h"
#include "tests/common/test_support.h"

using namespace flexsight;

TEST(Pyramid, DownsampleAveragesBlocksWithRoundingAndRepeatsOddBorders) {
  cv::Mat rgb(3, 3, CV_8UC3);
  const unsigned char grey[3][3] = {{1, 2, 10}, {3, 5, 20}, {100, 200, 255}};
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) rgb.at<cv::Vec3b>(y, x) = cv::Vec3b(grey[y][x], 0, 255);
  ViewImage coarse = downsample(make_view_image(rgb));
  ASSERT_EQ(coarse.width, 2);
  ASSERT_EQ(coarse.height, 2);
  // (1+2+3+5+2)/4 = 3.25 -> 3; (10+10+20+20+2)/4 -> 15; (100+200+100+200+2)/4 -> 150;
  // (255*4+2)/4 -> 255.
  EXPECT_EQ(coarse.color[0], 3.0f);
  EXPECT_EQ(coarse.color[4], 15.0f);
  EXPECT_EQ(coarse.color[8], 150.0f);
  EXPECT_EQ(coarse.color[12], 255.0f);
  EXPECT_EQ(coarse.color[1], 0.0f);
  EXPECT_EQ(coarse.color[2], 255.0f);
}

TEST(Pyramid, RoundsHalvesUp) {
  cv::Mat rgb(2, 2, CV_8UC3, cv::Scalar(0, 0, 0));
  rgb.at<cv::Vec3b>(0, 0) = cv::Vec3b(2, 1, 3);  // sums 2, 1, 3 -> 0.5, 0.25, 0.75
  ViewImage coarse = downsample(make_view_image(rgb));
  EXPECT_EQ(coarse.color[0], 1.0f);
  EXPECT_EQ(coarse.color[1], 0.0f);
  EXPECT_EQ(coarse.color[2], 1.0f);
}

TEST(Pyramid, GradientIsCentralDifferenceOfGrey) {
  cv::Mat rgb(3, 3, CV_8UC3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) rgb.at<cv::Vec3b>(y, x) = cv::Vec3b(10 * x + y, 10 * x + y, 10 * x + y);
  ViewImage image = make_view_image(rgb);
  // Centre: gx = (20 - 0) / 2 = 10, gy = (2 - 0) / 2 = 1; left border: (10 - 0) / 2 = 5.
  EXPECT_FLOAT_EQ(image.gradient[2 * 4], 10.0f);
  EXPECT_FLOAT_EQ(image.gradient[2 * 4 + 1], 1.0f);
  EXPECT_FLOAT_EQ(image.gradient[2 * 3], 5.0f);
}

TEST(Pyramid, LevelCountStopsAtTheCoarsestWidth) {
  EXPECT_EQ(pyramid_level_count(741, 497, 128), 4);  // 741 371 186 93
  EXPECT_EQ(pyramid_level_count(128, 100, 128), 1);
  EXPECT_EQ(pyramid_level_count(1241, 376, 128), 5);  // 1241 621 311 156 78
  EXPECT_EQ(pyramid_level_count(1000, 9, 128), 1);   // too flat to halve
}

TEST(Pyramid, BuildsLevelsOfHalvingSize) {
  auto pyramid = build_pyramid(testing_support::random_rgb8(101, 51, 1), 3);
  ASSERT_EQ(pyramid.size(), 3u);
  EXPECT_EQ(pyramid[1].width, 51);
  EXPECT_EQ(pyramid[1].height, 26);
  EXPECT_EQ(pyramid[2].width, 26);
  EXPECT_EQ(pyramid[2].height, 13);
}

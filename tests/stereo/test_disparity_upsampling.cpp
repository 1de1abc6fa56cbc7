// upsample_disparity (host/stereo/disparity_upsampling.h): pick's disparity from a pair
// matched at a fraction of its size.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "host/stereo/disparity_upsampling.h"

namespace flexsight {
namespace {

// A slanted plane d = a x + b y + c in the small image's pixels, with its planes.
void slanted_plane(cv::Size size, float a, float b, float c, cv::Mat& disparity, cv::Mat& planes) {
  disparity.create(size, CV_32FC1);
  planes.create(size, CV_32FC3);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      disparity.at<float>(y, x) = a * x + b * y + c;
      planes.at<cv::Vec3f>(y, x) = cv::Vec3f(a, b, c);
    }
  }
}

// The same surface seen at twice the size: d_full(X, Y) = 2 d_small((X + 0.5) / 2 - 0.5, ...).
TEST(DisparityUpsampling, FollowsASlantedPlaneExactlyAtTwiceTheSize) {
  cv::Mat small, planes;
  const float a = 0.125f, b = -0.0625f, c = 20.0f;
  slanted_plane({40, 30}, a, b, c, small, planes);
  const cv::Mat full = upsample_disparity(small, planes, {80, 60});
  ASSERT_EQ(full.size(), cv::Size(80, 60));
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 80; ++x) {
      const double xs = (x + 0.5) / 2 - 0.5, ys = (y + 0.5) / 2 - 0.5;
      EXPECT_NEAR(full.at<float>(y, x), 2.0 * (a * xs + b * ys + c), 1e-4) << x << "," << y;
    }
  }
}

// A step between two fronto-parallel surfaces stays a step: no pixel takes a value between them.
TEST(DisparityUpsampling, KeepsADepthEdgeSharp) {
  cv::Mat small(20, 20, CV_32FC1), planes(20, 20, CV_32FC3, cv::Scalar(0, 0, 0));
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 20; ++x) small.at<float>(y, x) = x < 10 ? 10.0f : 30.0f;
  }
  const cv::Mat full = upsample_disparity(small, planes, {60, 60});
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 60; ++x) {
      const float d = full.at<float>(y, x);
      EXPECT_TRUE(d == 30.0f || d == 90.0f) << x << "," << y << ": " << d;
      EXPECT_EQ(d, x < 30 ? 30.0f : 90.0f) << x << "," << y;
    }
  }
}

TEST(DisparityUpsampling, APixelWithoutAFinitePlaneKeepsItsScaledDisparity) {
  cv::Mat small, planes;
  slanted_plane({8, 8}, 0.0f, 0.0f, 5.0f, small, planes);
  planes.at<cv::Vec3f>(3, 3) = cv::Vec3f(std::numeric_limits<float>::quiet_NaN(), 0.0f, 5.0f);
  small.at<float>(5, 5) = std::numeric_limits<float>::infinity();
  const cv::Mat full = upsample_disparity(small, planes, {16, 16});
  EXPECT_EQ(full.at<float>(6, 6), 10.0f);
  EXPECT_EQ(full.at<float>(7, 7), 10.0f);
  EXPECT_TRUE(std::isinf(full.at<float>(10, 10)));
}

TEST(DisparityUpsampling, RefusesPlanesOfAnotherSize) {
  cv::Mat small(8, 8, CV_32FC1, cv::Scalar(1)), planes(4, 4, CV_32FC3, cv::Scalar(0, 0, 1));
  EXPECT_THROW(upsample_disparity(small, planes, {16, 16}), std::invalid_argument);
}

}  // namespace
}  // namespace flexsight

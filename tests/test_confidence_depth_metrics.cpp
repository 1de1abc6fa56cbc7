// Confidence-threshold and depth-error metrics on hand-made maps.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "host/eval/confidence_depth_metrics.h"

using namespace flexsight;

namespace {

const float kInf = std::numeric_limits<float>::infinity();

// One row of four pixels: 2 right, 1 wrong, 1 without ground truth.
struct Maps {
  cv::Mat disparity = (cv::Mat_<float>(1, 4) << 10.0f, 20.0f, 30.0f, 40.0f);
  cv::Mat truth = (cv::Mat_<float>(1, 4) << 10.5f, 20.0f, 25.0f, kInf);
  cv::Mat confidence = (cv::Mat_<float>(1, 4) << 0.9f, 0.3f, 0.6f, 1.0f);
};

}  // namespace

TEST(ConfidentStats, DensityAndBad2AmongPixelsAboveEachThreshold) {
  const Maps m;
  const ConfidentStats stats = evaluate_confident(m.disparity, m.truth, m.confidence);
  ASSERT_TRUE(stats.available);
  // C >= 0.25: all 3 pixels with truth, 1 bad. C >= 0.5: pixels 0 and 2, 1 bad.
  // C >= 0.75: pixel 0 only, good.
  EXPECT_DOUBLE_EQ(stats.density_percent[0], 100.0);
  EXPECT_DOUBLE_EQ(stats.bad2_percent[0], 100.0 / 3);
  EXPECT_DOUBLE_EQ(stats.density_percent[1], 200.0 / 3);
  EXPECT_DOUBLE_EQ(stats.bad2_percent[1], 50.0);
  EXPECT_DOUBLE_EQ(stats.density_percent[2], 100.0 / 3);
  EXPECT_DOUBLE_EQ(stats.bad2_percent[2], 0.0);
  EXPECT_FALSE(evaluate_confident(m.disparity, m.truth, cv::Mat()).available);
}

TEST(DepthStats, MedianAbsoluteDepthErrorInMillimetres) {
  Maps m;
  StereoCamera camera;  // Z = f B / (d + doffs) with f 100 px, B 0.1 m, doffs 0
  camera.Q = reprojection_matrix(100, 0, 0, 0, 0.1);
  camera.unit = "m";
  camera.metres_per_unit = 1.0;
  const DepthStats stats = evaluate_depth(m.disparity, m.truth, m.confidence, camera);
  ASSERT_TRUE(stats.available);
  // |10/10 - 10/10.5|, |10/20 - 10/20|, |10/30 - 10/25| in m -> mm; median of three.
  const double e0 = std::abs(10.0 / 10 - 10.0 / 10.5) * 1e3;
  const double e2 = std::abs(10.0 / 30 - 10.0 / 25) * 1e3;
  EXPECT_NEAR(stats.median_abs_mm_all, e0, 1e-6);
  EXPECT_NEAR(stats.median_abs_mm_confident, 0.5 * (e0 + e2), 1e-6);  // pixels 0 and 2

  // A pixel without a result is an infinite error: the median moves up.
  m.disparity.at<float>(0, 1) = -1.0f;
  EXPECT_NEAR(evaluate_depth(m.disparity, m.truth, {}, camera).median_abs_mm_all, e2, 1e-6);
  EXPECT_TRUE(std::isnan(evaluate_depth(m.disparity, m.truth, {}, camera).median_abs_mm_confident));
}

// Confidence-threshold and depth-error metrics on hand-made maps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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

namespace {

// The sparsification area written out for 20 pixels kept 1, 2, ..., 20 at a time:
// the mean over k of (bad pixels among the first k) / k, in percent.
double area_of_order(const std::vector<bool>& bad_in_rank_order) {
  double sum = 0, bad = 0;
  for (size_t k = 1; k <= bad_in_rank_order.size(); ++k) {
    bad += bad_in_rank_order[k - 1];
    sum += bad / double(k);
  }
  return 100.0 * sum / double(bad_in_rank_order.size());
}

}  // namespace

TEST(Sparsification, TwentyPixelsRankedWellBadlyAndAllTied) {
  // Pixel i has rank i; pixels 3, 7, 11, 12 and 18 are bad.
  std::vector<float> rank(20);
  std::vector<bool> bad(20, false);
  for (int i = 0; i < 20; ++i) rank[i] = float(i);
  for (int i : {3, 7, 11, 12, 18}) bad[i] = true;
  // Descending rank visits pixel 19 first.
  std::vector<bool> visited;
  for (int i = 19; i >= 0; --i) visited.push_back(bad[i]);
  EXPECT_NEAR(sparsification_auc_percent(rank, bad), area_of_order(visited), 1e-9);

  // The bad pixels ranked last give the optimum, ranked first the worst case.
  std::vector<bool> last(20, false), first(20, false);
  for (int i = 15; i < 20; ++i) last[i] = true;
  for (int i = 0; i < 5; ++i) first[i] = true;
  std::vector<float> negative_error(20);
  for (int i = 0; i < 20; ++i) negative_error[i] = -float(bad[i]);
  EXPECT_NEAR(sparsification_auc_percent(negative_error, bad), area_of_order(last), 1e-9);
  for (int i = 0; i < 20; ++i) negative_error[i] = float(bad[i]);
  EXPECT_NEAR(sparsification_auc_percent(negative_error, bad), area_of_order(first), 1e-9);
  EXPECT_LT(area_of_order(last), sparsification_auc_percent(rank, bad));
  // The curve behind the worst case: the first k pixels hold min(k, 5) bad ones.
  const auto worst = sparsification_curve_percent(negative_error, bad);
  for (int k = 1; k <= 20; ++k) EXPECT_NEAR(worst[k - 1], 100.0 * std::min(k, 5) / k, 1e-9) << k;

  // One block of equal rank: every step keeps a proportional share of its bad pixels,
  // 5 of 20, whatever order the sort leaves them in.
  EXPECT_NEAR(sparsification_auc_percent(std::vector<float>(20, 0.5f), bad), 25.0, 1e-9);
  EXPECT_EQ(sparsification_auc_percent({}, {}), 0.0);
}

TEST(Sparsification, EvaluateConfidentRanksThePixelsWithGroundTruth) {
  const Maps m;  // with truth: C 0.9 good, 0.3 good, 0.6 bad
  const ConfidentStats stats = evaluate_confident(m.disparity, m.truth, m.confidence);
  EXPECT_DOUBLE_EQ(stats.sparsification_auc_percent,
                   sparsification_auc_percent({0.9f, 0.3f, 0.6f}, {false, false, true}));
  // By the true error the bad pixel comes last.
  EXPECT_DOUBLE_EQ(stats.optimal_auc_percent,
                   sparsification_auc_percent({3.0f, 2.0f, 1.0f}, {false, false, true}));
  EXPECT_LT(stats.optimal_auc_percent, stats.sparsification_auc_percent);
  // Three pixels in 20 steps: the first steps keep one pixel (C 0.9, good), the middle
  // ones two (with the bad C 0.6), the last ones all three.
  EXPECT_DOUBLE_EQ(stats.sparsification_curve_percent[0], 0.0);
  EXPECT_DOUBLE_EQ(stats.sparsification_curve_percent[9], 50.0);
  EXPECT_DOUBLE_EQ(stats.sparsification_curve_percent[19], 100.0 / 3);
  EXPECT_DOUBLE_EQ(stats.optimal_curve_percent[9], 0.0);
}

// Benchmark metrics (MiddEval3 conventions) and the pictures drawn from them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "host/eval/colorize.h"
#include "host/eval/metrics.h"
#include "tests/common/mat_rows.h"

namespace flexsight {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Index of each threshold in ErrorStats::bad_percent.
enum { kBad05, kBad1, kBad2, kBad3, kBad4 };

using testing_support::rows_to_mask;
using testing_support::rows_to_mat;

// A 5x2 case covering every rule. Errors |d - gt| per pixel (x, y):
//   (0,0) 0     (1,0) 0.5 = threshold 0.5, not bad there   (2,0) 1.0 = threshold 1
//   (3,0) 3.0 occluded (mask 128), exactly threshold 3      (4,0) unknown GT: skipped
//   (0,1) NaN: no result   (1,1) -1: no result   (2,1) 2.0 = threshold 2
//   (3,1) 4.5 bad everywhere   (4,1) 0.25
struct HandCase {
  cv::Mat gt = rows_to_mat({{10, 10, 10, 10, kInf}, {20, 20, 20, 20, 20}});
  cv::Mat disparity = rows_to_mat({{10, 10.5f, 11, 13, 5}, {kNaN, -1, 22, 24.5f, 20.25f}});
  cv::Mat mask = rows_to_mask({{255, 255, 255, 128, 0}, {255, 255, 255, 255, 255}});
};

TEST(EvaluateDisparity, HandComputedCaseAllPixels) {
  const HandCase c;
  const ErrorStats all = evaluate_disparity(c.disparity, c.gt, c.mask).all;
  // Evaluated: 9 pixels with finite GT. With a result: 7 (all but NaN and -1).
  EXPECT_EQ(all.evaluated, 9);
  // > 0.5: errors 1, 3, 2, 4.5 plus 2 without result = 6 of 9.
  EXPECT_NEAR(all.bad_percent[kBad05], 100.0 * 6 / 9, 1e-9);
  // > 1: 3, 2, 4.5 + 2 = 5 of 9 (the error of exactly 1 is good).
  EXPECT_NEAR(all.bad_percent[kBad1], 100.0 * 5 / 9, 1e-9);
  // > 2: 3, 4.5 + 2 = 4 of 9 (the error of exactly 2 is good).
  EXPECT_NEAR(all.bad_percent[kBad2], 100.0 * 4 / 9, 1e-9);
  // > 3: 4.5 + 2 = 3 of 9 (the occluded error of exactly 3 is good).
  EXPECT_NEAR(all.bad_percent[kBad3], 100.0 * 3 / 9, 1e-9);
  // > 4: 4.5 + 2 = 3 of 9.
  EXPECT_NEAR(all.bad_percent[kBad4], 100.0 * 3 / 9, 1e-9);
  // Average over the 7 with a result: (0 + 0.5 + 1 + 3 + 2 + 4.5 + 0.25) / 7 = 11.25 / 7.
  EXPECT_NEAR(all.avg_error, 11.25 / 7, 1e-9);
  // Density: 7 of 9.
  EXPECT_NEAR(all.density_percent, 100.0 * 7 / 9, 1e-9);
}

TEST(EvaluateDisparity, HandComputedCaseNonOccluded) {
  const HandCase c;
  const ErrorStats nonocc = evaluate_disparity(c.disparity, c.gt, c.mask).nonocc;
  // The occluded (3,0) drops out (and (4,0) has no GT): 8 evaluated, 6 with a result.
  EXPECT_EQ(nonocc.evaluated, 8);
  EXPECT_DOUBLE_EQ(nonocc.bad_percent[kBad05], 62.5);  // 1, 2, 4.5 + 2 = 5 of 8
  EXPECT_DOUBLE_EQ(nonocc.bad_percent[kBad1], 50.0);   // 2, 4.5 + 2 = 4 of 8
  EXPECT_DOUBLE_EQ(nonocc.bad_percent[kBad2], 37.5);   // 4.5 + 2 = 3 of 8
  EXPECT_DOUBLE_EQ(nonocc.bad_percent[kBad3], 37.5);
  EXPECT_DOUBLE_EQ(nonocc.bad_percent[kBad4], 37.5);
  // (0 + 0.5 + 1 + 2 + 4.5 + 0.25) / 6 = 8.25 / 6 = 1.375.
  EXPECT_DOUBLE_EQ(nonocc.avg_error, 1.375);
  EXPECT_DOUBLE_EQ(nonocc.density_percent, 75.0);  // 6 of 8
}

TEST(EvaluateDisparity, BadByThresholdValue) {
  const HandCase c;
  const ErrorStats nonocc = evaluate_disparity(c.disparity, c.gt, c.mask).nonocc;
  EXPECT_DOUBLE_EQ(nonocc.bad(0.5), 62.5);
  EXPECT_DOUBLE_EQ(nonocc.bad(2.0), 37.5);
  EXPECT_THROW(nonocc.bad(1.5), std::invalid_argument);
}

TEST(EvaluateDisparity, InfiniteResultIsMissing) {
  // One pixel, error 0, one +inf: 50% bad at every threshold, density 50%, avg error 0.
  const cv::Mat gt = rows_to_mat({{3, 3}});
  const ErrorStats all = evaluate_disparity(rows_to_mat({{3, kInf}}), gt, cv::Mat()).all;
  for (double percent : all.bad_percent) EXPECT_DOUBLE_EQ(percent, 50.0);
  EXPECT_DOUBLE_EQ(all.avg_error, 0.0);
  EXPECT_DOUBLE_EQ(all.density_percent, 50.0);
}

TEST(EvaluateDisparity, NoResultAtAllHasNoAverageError) {
  // Ground truth everywhere, no result anywhere: every pixel bad, density 0, and the
  // average error undefined (NaN, "n/a" in reports) rather than a perfect 0.
  const cv::Mat gt = rows_to_mat({{3, 4, 5}});
  const ErrorStats all = evaluate_disparity(rows_to_mat({{kNaN, kNaN, kNaN}}), gt, cv::Mat()).all;
  EXPECT_EQ(all.evaluated, 3);
  for (double percent : all.bad_percent) EXPECT_DOUBLE_EQ(percent, 100.0);
  EXPECT_DOUBLE_EQ(all.density_percent, 0.0);
  EXPECT_TRUE(std::isnan(all.avg_error));
}

TEST(AverageStats, AveragesTheErrorOverScenesThatHaveOne) {
  ErrorStats a, b;
  a.avg_error = 1.5;
  b.avg_error = std::numeric_limits<double>::quiet_NaN();
  EXPECT_DOUBLE_EQ(average({a, b}).avg_error, 1.5);
  EXPECT_TRUE(std::isnan(average({b, b}).avg_error));
}

TEST(EvaluateDisparity, EmptyMaskMeansEverythingNonOccluded) {
  const HandCase c;
  const SceneScores scores = evaluate_disparity(c.disparity, c.gt, cv::Mat());
  EXPECT_EQ(scores.nonocc.evaluated, 9);
  EXPECT_EQ(scores.nonocc.bad_percent, scores.all.bad_percent);
  EXPECT_DOUBLE_EQ(scores.nonocc.avg_error, scores.all.avg_error);
}

TEST(EvaluateDisparity, SelectionRestrictsBothRegions) {
  const HandCase c;
  // Select row 0 only: (0,0) 0, (1,0) 0.5, (2,0) 1, (3,0) 3 occluded; (4,0) has no GT.
  const cv::Mat selection = rows_to_mask({{1, 1, 1, 1, 1}, {0, 0, 0, 0, 0}});
  const SceneScores scores = evaluate_disparity(c.disparity, c.gt, c.mask, selection);
  EXPECT_EQ(scores.all.evaluated, 4);
  EXPECT_DOUBLE_EQ(scores.all.bad_percent[kBad05], 50.0);  // 1 and 3
  EXPECT_DOUBLE_EQ(scores.all.avg_error, 4.5 / 4);
  EXPECT_EQ(scores.nonocc.evaluated, 3);
  EXPECT_DOUBLE_EQ(scores.nonocc.avg_error, 0.5);  // (0 + 0.5 + 1) / 3
  EXPECT_DOUBLE_EQ(scores.nonocc.density_percent, 100.0);
}

TEST(EvaluateDisparity, NoGroundTruthGivesZerosNotNaN) {
  const cv::Mat gt = rows_to_mat({{kInf, kInf}});
  const ErrorStats all = evaluate_disparity(rows_to_mat({{1, 2}}), gt, cv::Mat()).all;
  EXPECT_EQ(all.evaluated, 0);
  EXPECT_EQ(all.avg_error, 0.0);
  EXPECT_EQ(all.density_percent, 0.0);
  EXPECT_EQ(all.bad_percent[kBad2], 0.0);
}

TEST(EvaluateDisparity, RejectsSizeAndTypeMismatch) {
  const cv::Mat d(4, 5, CV_32FC1, cv::Scalar(1));
  const cv::Mat gt(4, 5, CV_32FC1, cv::Scalar(1));
  EXPECT_THROW(evaluate_disparity(d, cv::Mat(5, 4, CV_32FC1, cv::Scalar(1)), cv::Mat()),
               std::invalid_argument);
  EXPECT_THROW(evaluate_disparity(cv::Mat(4, 5, CV_64FC1, cv::Scalar(1)), gt, cv::Mat()),
               std::invalid_argument);
  EXPECT_THROW(evaluate_disparity(d, cv::Mat(4, 5, CV_16UC1, cv::Scalar(1)), cv::Mat()),
               std::invalid_argument);
  EXPECT_THROW(evaluate_disparity(cv::Mat(), cv::Mat(), cv::Mat()), std::invalid_argument);
  EXPECT_THROW(evaluate_disparity(d, gt, cv::Mat(4, 5, CV_16UC1, cv::Scalar(255))),
               std::invalid_argument);
  EXPECT_THROW(evaluate_disparity(d, gt, cv::Mat(4, 4, CV_8UC1, cv::Scalar(255))),
               std::invalid_argument);
  EXPECT_THROW(evaluate_disparity(d, gt, cv::Mat(), cv::Mat(3, 5, CV_8UC1, cv::Scalar(1))),
               std::invalid_argument);
  // The matching sizes and types are accepted, and this perfect result scores as one.
  SceneScores perfect;
  ASSERT_NO_THROW(perfect = evaluate_disparity(d, gt, cv::Mat(4, 5, CV_8UC1, cv::Scalar(255))));
  for (const ErrorStats* stats : {&perfect.all, &perfect.nonocc}) {
    EXPECT_EQ(stats->evaluated, 20);
    for (double percent : stats->bad_percent) EXPECT_EQ(percent, 0.0);
    EXPECT_EQ(stats->avg_error, 0.0);
    EXPECT_EQ(stats->density_percent, 100.0);
  }
}

// The metric definitions restated as plain loops, independent of the implementation.
struct BruteForce {
  long evaluated = 0;
  long with_result = 0;
  long bad[5] = {0, 0, 0, 0, 0};
  double error_sum = 0;
};

TEST(EvaluateDisparity, MatchesBruteForceOnRandomCase) {
  const int width = 50, height = 40;
  cv::RNG rng(20240611);
  cv::Mat gt(height, width, CV_32FC1), d(height, width, CV_32FC1), mask(height, width, CV_8UC1);
  const uchar mask_values[3] = {0, 128, 255};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float truth = static_cast<float>(rng.uniform(0, 60));
      gt.at<float>(y, x) = rng.uniform(0, 10) == 0 ? kInf : truth;
      const int kind = rng.uniform(0, 10);
      float value = truth + rng.uniform(-6.0f, 6.0f);
      // Offsets in quarter pixels often land exactly on a threshold.
      if (kind < 3) value = truth + 0.25f * static_cast<float>(rng.uniform(-20, 21));
      if (kind == 3) value = kNaN;
      if (kind == 4) value = -0.5f;
      d.at<float>(y, x) = value;
      mask.at<uchar>(y, x) = mask_values[rng.uniform(0, 3)];
    }
  }
  const double thresholds[5] = {0.5, 1, 2, 3, 4};
  BruteForce all, nonocc;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float truth = gt.at<float>(y, x);
      if (!std::isfinite(truth)) continue;
      const float value = d.at<float>(y, x);
      const bool valid = std::isfinite(value) && value >= 0;
      const double error = valid ? std::fabs(static_cast<double>(value) - truth) : 0.0;
      for (BruteForce* region : {&all, &nonocc}) {
        if (region == &nonocc && mask.at<uchar>(y, x) != 255) continue;
        region->evaluated++;
        if (valid) {
          region->with_result++;
          region->error_sum += error;
        }
        for (int t = 0; t < 5; ++t) {
          if (!valid || error > thresholds[t]) region->bad[t]++;
        }
      }
    }
  }
  const SceneScores scores = evaluate_disparity(d, gt, mask);
  const std::pair<const ErrorStats*, const BruteForce*> regions[] = {{&scores.all, &all},
                                                                      {&scores.nonocc, &nonocc}};
  for (const auto& [stats, expected] : regions) {
    ASSERT_GT(expected->evaluated, 100);
    EXPECT_EQ(stats->evaluated, expected->evaluated);
    for (int t = 0; t < 5; ++t) {
      EXPECT_NEAR(stats->bad_percent[t], 100.0 * expected->bad[t] / expected->evaluated, 1e-9);
    }
    EXPECT_NEAR(stats->avg_error, expected->error_sum / expected->with_result, 1e-9);
    EXPECT_NEAR(stats->density_percent, 100.0 * expected->with_result / expected->evaluated, 1e-9);
  }
}

TEST(Average, IsUnweightedMeanOfEachField) {
  ErrorStats a, b;
  a.bad_percent = {10, 20, 30, 40, 50};
  b.bad_percent = {0, 10, 0, 10, 0};
  a.avg_error = 1.5;
  b.avg_error = 0.5;
  a.density_percent = 100;
  b.density_percent = 80;
  a.evaluated = 1000;  // weights do not matter: still a plain mean
  b.evaluated = 10;
  const ErrorStats mean = average({a, b});
  EXPECT_DOUBLE_EQ(mean.bad_percent[kBad05], 5.0);
  EXPECT_DOUBLE_EQ(mean.bad_percent[kBad1], 15.0);
  EXPECT_DOUBLE_EQ(mean.bad_percent[kBad2], 15.0);
  EXPECT_DOUBLE_EQ(mean.bad_percent[kBad3], 25.0);
  EXPECT_DOUBLE_EQ(mean.bad_percent[kBad4], 25.0);
  EXPECT_DOUBLE_EQ(mean.avg_error, 1.0);
  EXPECT_DOUBLE_EQ(mean.density_percent, 90.0);
  EXPECT_EQ(mean.evaluated, 505);

  const ErrorStats single = average({a});
  EXPECT_EQ(single.bad_percent, a.bad_percent);
  const ErrorStats none = average({});
  EXPECT_EQ(none.evaluated, 0);
  EXPECT_EQ(none.avg_error, 0.0);
}

// ---- pictures --------------------------------------------------------------------

cv::Vec3b turbo_rgb(int level) {
  cv::Mat gray(1, 1, CV_8UC1, cv::Scalar(level)), bgr;
  cv::applyColorMap(gray, bgr, cv::COLORMAP_TURBO);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  return cv::Vec3b(c[2], c[1], c[0]);
}

TEST(ColorizeDisparity, SizeTypeAndBlackForMissing) {
  const cv::Mat d = rows_to_mat({{0, 32, 64, 100}, {kNaN, -1, kInf, 16}});
  const cv::Mat rgb = colorize_disparity(d, 64);
  ASSERT_EQ(rgb.type(), CV_8UC3);
  ASSERT_EQ(rgb.size(), d.size());
  const cv::Vec3b black(0, 0, 0);
  EXPECT_EQ(rgb.at<cv::Vec3b>(1, 0), black);  // NaN
  EXPECT_EQ(rgb.at<cv::Vec3b>(1, 1), black);  // negative
  EXPECT_EQ(rgb.at<cv::Vec3b>(1, 2), black);  // +inf
  EXPECT_NE(rgb.at<cv::Vec3b>(0, 0), black);  // zero disparity is a result, not black
  EXPECT_NE(rgb.at<cv::Vec3b>(1, 3), black);
}

TEST(ColorizeDisparity, TurboInRgbOrder) {
  const cv::Mat rgb = colorize_disparity(rows_to_mat({{0, 64, 200}}), 64);
  EXPECT_EQ(rgb.at<cv::Vec3b>(0, 0), turbo_rgb(0));
  EXPECT_EQ(rgb.at<cv::Vec3b>(0, 1), turbo_rgb(255));
  EXPECT_EQ(rgb.at<cv::Vec3b>(0, 2), turbo_rgb(255));  // saturates past the maximum
  // Turbo runs from dark blue to dark red: in RGB order, blue dominates red at 0.
  EXPECT_GT(rgb.at<cv::Vec3b>(0, 0)[2], rgb.at<cv::Vec3b>(0, 0)[0]);
  EXPECT_GT(rgb.at<cv::Vec3b>(0, 1)[0], rgb.at<cv::Vec3b>(0, 1)[2]);
}

TEST(ColorizeDisparity, RejectsBadInput) {
  EXPECT_THROW(colorize_disparity(cv::Mat(2, 2, CV_8UC1), 10), std::invalid_argument);
  EXPECT_THROW(colorize_disparity(cv::Mat(2, 2, CV_32FC1, cv::Scalar(1)), 0), std::invalid_argument);
}

TEST(ErrorMap, ColorsPerCategory) {
  // Threshold 2. Row 0 non-occluded, row 1 the same pixels occluded (mask 128).
  //   x: 0 unknown GT, 1 no result, 2 error 0, 3 error 2 (= threshold), 4 error 2.5,
  //      5 error 8 (= 4 * threshold), 6 error 20
  const cv::Mat gt = rows_to_mat({{kInf, 5, 5, 5, 5, 5, 5}, {kInf, 5, 5, 5, 5, 5, 5}});
  const cv::Mat d = rows_to_mat({{3, kNaN, 5, 7, 7.5f, 13, 25}, {3, kNaN, 5, 7, 7.5f, 13, 25}});
  const cv::Mat mask = rows_to_mask({{255, 255, 255, 255, 255, 255, 255}, {128, 128, 128, 128, 128, 128, 128}});
  const cv::Mat rgb = error_map(d, gt, mask, 2.0f);
  ASSERT_EQ(rgb.type(), CV_8UC3);
  ASSERT_EQ(rgb.size(), d.size());
  auto at = [&](int x, int y) { return rgb.at<cv::Vec3b>(y, x); };

  EXPECT_EQ(at(0, 0), cv::Vec3b(0, 0, 0));        // unknown: black
  EXPECT_EQ(at(1, 0), cv::Vec3b(255, 0, 255));    // no result: magenta
  EXPECT_EQ(at(2, 0), cv::Vec3b(0, 255, 0));      // exact: bright green
  const cv::Vec3b at_threshold = at(3, 0);        // still good: a green shade
  EXPECT_EQ(at_threshold[0], 0);
  EXPECT_EQ(at_threshold[2], 0);
  EXPECT_GT(at_threshold[1], 0);
  EXPECT_LT(at_threshold[1], 255);
  const cv::Vec3b just_bad = at(4, 0);            // bad: between yellow and red
  EXPECT_EQ(just_bad[0], 255);
  EXPECT_EQ(just_bad[2], 0);
  EXPECT_GT(just_bad[1], 128);
  EXPECT_EQ(at(5, 0), cv::Vec3b(255, 0, 0));      // saturated red at 4 * threshold
  EXPECT_EQ(at(6, 0), cv::Vec3b(255, 0, 0));

  // Occluded pixels: the same hue at half brightness; unknown stays black.
  EXPECT_EQ(at(0, 1), cv::Vec3b(0, 0, 0));
  for (int x = 1; x < 7; ++x) {
    const cv::Vec3b bright = at(x, 0), dark = at(x, 1);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(dark[c], bright[c] / 2) << "x=" << x << " c=" << c;
  }
}

TEST(ErrorMap, EmptyMaskAndRejectedInput) {
  const cv::Mat gt = rows_to_mat({{1, 1}});
  const cv::Mat rgb = error_map(rows_to_mat({{1, 1}}), gt, cv::Mat(), 2.0f);
  EXPECT_EQ(rgb.at<cv::Vec3b>(0, 1), cv::Vec3b(0, 255, 0));
  EXPECT_THROW(error_map(rows_to_mat({{1}}), gt, cv::Mat(), 2.0f), std::invalid_argument);
  EXPECT_THROW(error_map(gt, gt, cv::Mat(1, 2, CV_32FC1), 2.0f), std::invalid_argument);
}

}  // namespace
}  // namespace flexsight

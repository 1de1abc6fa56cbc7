// evaluate_breakdown (host/eval/detection_breakdown.h): class-agnostic AP and AP and
// recall by part size, on box sets small enough to work out by hand (each expected
// value's arithmetic in the comment beside it).
#include "host/eval/detection_breakdown.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>
#include "tests/eval/detection_boxes.h"

namespace flexsight {
namespace {

using namespace detection_boxes;

const SizeFigures& bin_named(const DetectionBreakdown& b, const std::string& label) {
  for (const SizeFigures& size : b.sizes) {
    if (size.bin.label == label) return size;
  }
  throw std::logic_error("no size bin " + label);
}

TEST(EvalDetBreakdown, SizeBinsAreHalfOpenOnSqrtArea) {
  const std::vector<SizeBin> bins = default_size_bins();
  ASSERT_EQ(bins.size(), 4u);
  EXPECT_EQ(box_size_px({0, 0, 32, 32}), 32.0);
  EXPECT_EQ(box_size_px({0, 0, 16, 64}), 32.0);  // sqrt(area), not the width
  EXPECT_FALSE(bins[0].range.contains({0, 0, 32, 32}));
  EXPECT_TRUE(bins[1].range.contains({0, 0, 32, 32}));
  EXPECT_TRUE(bins[0].range.contains({0, 0, 31, 32}));
  EXPECT_TRUE(bins[3].range.contains({0, 0, 128, 128}));
  EXPECT_TRUE(bins[3].range.contains({0, 0, 5000, 5000}));
}

TEST(EvalDetBreakdown, WrongClassIsFoundButNotNamed) {
  // A: class 1, 40 px; B: class 2, 100 px. Both found, A under class 2.
  const std::vector<std::vector<TruthBox>> gt = {{truth(1, 0, 0, 40, 40), truth(2, 100, 100, 100, 100)}};
  const std::vector<std::vector<DetectedBox>> dets = {
      {detected(2, 0, 0, 40, 40, 0.9), detected(2, 100, 100, 100, 100, 0.2)}};
  const DetectionBreakdown b = evaluate_breakdown(gt, dets, kTwoClasses);
  // Per class: class 1 has no detection (AP 0); class 2: the 0.9 box is a false positive,
  // then B: precision 0, 1/2 at recall 0, 1 -> envelope 1/2, AP 0.5. Mean 0.25.
  EXPECT_EQ(b.per_class.ground_truth, 2);
  EXPECT_NEAR(b.per_class.ap50, 0.25, kTight);
  EXPECT_NEAR(b.per_class.recall_any, 0.5, kTight);     // B only
  EXPECT_NEAR(b.per_class.recall_at_score, 0.0, kTight);  // B's box scores 0.2 < 0.3
  // Class-agnostic: both boxes match, AP 1, and exact boxes make every COCO threshold 1.
  EXPECT_NEAR(b.agnostic.ap50, 1.0, kTight);
  EXPECT_NEAR(b.agnostic_coco_ap, 1.0, kTight);
  EXPECT_NEAR(b.agnostic.recall_any, 1.0, kTight);
  EXPECT_NEAR(b.agnostic.recall_at_score, 0.5, kTight);  // A at 0.9; B's 0.2 is below 0.3

  // 32-64 px holds A: per class only class 1 has ground truth there, undetected -> 0;
  // class-agnostic the 0.9 box matches A, and the 0.2 box matches B, of another size:
  // ignored, not a false positive -> AP 1.
  const SizeFigures& small = bin_named(b, "32-64");
  EXPECT_EQ(small.per_class.ground_truth, 1);
  EXPECT_NEAR(small.per_class.ap50, 0.0, kTight);
  EXPECT_NEAR(small.agnostic.ap50, 1.0, kTight);
  EXPECT_NEAR(small.agnostic.recall_any, 1.0, kTight);
  // 64-128 px holds B: class 2's 0.9 box matches nothing and is 40 px, outside the
  // range: ignored -> AP 1 (class 1 has no ground truth there and enters no mean).
  const SizeFigures& large = bin_named(b, "64-128");
  EXPECT_EQ(large.per_class.ground_truth, 1);
  EXPECT_NEAR(large.per_class.ap50, 1.0, kTight);
  EXPECT_NEAR(large.per_class.recall_any, 1.0, kTight);
  EXPECT_NEAR(large.per_class.recall_at_score, 0.0, kTight);
  // Bins without ground truth: no figure.
  EXPECT_EQ(bin_named(b, "<32").agnostic.ground_truth, 0);
  EXPECT_TRUE(std::isnan(bin_named(b, "<32").agnostic.ap50));
  EXPECT_TRUE(std::isnan(bin_named(b, ">=128").per_class.recall_any));
}

TEST(EvalDetBreakdown, PartFoundUnderTwoClassesIsOneMatchAndOneFalsePositive) {
  // Two class-1 parts of 50 px; the first found as class 2 (0.9) and class 1 (0.6), the
  // second as class 1 (0.5).
  const std::vector<std::vector<TruthBox>> gt = {{truth(1, 0, 0, 50, 50), truth(1, 100, 0, 50, 50)}};
  const std::vector<std::vector<DetectedBox>> dets = {
      {detected(2, 0, 0, 50, 50, 0.9), detected(1, 0, 0, 50, 50, 0.6), detected(1, 100, 0, 50, 50, 0.5)}};
  const DetectionBreakdown b = evaluate_breakdown(gt, dets, kTwoClasses);
  // Per class: class 1's two boxes both match -> AP 1; class 2 has no ground truth.
  EXPECT_NEAR(b.per_class.ap50, 1.0, kTight);
  // Class-agnostic: 0.9 TP (p 1, r 1/2), 0.6 FP on the same part (p 1/2), 0.5 TP (p 2/3,
  // r 1): envelope 1 up to recall 1/2, 2/3 to 1 -> AP 1/2 + 1/3 = 5/6.
  EXPECT_NEAR(b.agnostic.ap50, 5.0 / 6.0, kTight);
  EXPECT_NEAR(b.agnostic.recall_any, 1.0, kTight);
  EXPECT_NEAR(bin_named(b, "32-64").agnostic.ap50, 5.0 / 6.0, kTight);
}

TEST(EvalDetBreakdown, RecallCountsMatchesFromTheScore) {
  const std::vector<std::vector<TruthBox>> gt = {
      {truth(1, 0, 0, 50, 50), truth(1, 100, 0, 50, 50), truth(1, 300, 0, 20, 20, /*crowd=*/true)}};
  // 0.5 and 0.1 match; 0.05 lies nowhere (a false positive); 0.7 covers the crowd region
  // (ignored).
  const std::vector<std::vector<DetectedBox>> dets = {{detected(1, 2, 0, 50, 50, 0.5),
                                                       detected(1, 100, 0, 50, 50, 0.1),
                                                       detected(1, 200, 200, 50, 50, 0.05),
                                                       detected(1, 300, 0, 20, 20, 0.7)}};
  DetectionBreakdownOptions options;
  options.recall_score = 0.3;
  const DetectionBreakdown at_03 = evaluate_breakdown(gt, dets, kTwoClasses, options);
  EXPECT_EQ(at_03.per_class.ground_truth, 2);  // the crowd region is no target
  EXPECT_NEAR(at_03.per_class.recall_at_score, 0.5, kTight);
  EXPECT_NEAR(at_03.per_class.recall_any, 1.0, kTight);
  // TP (p 1, r 1/2), TP (p 1, r 1), FP: AP 1.
  EXPECT_NEAR(at_03.per_class.ap50, 1.0, kTight);
  options.recall_score = 0.1;  // a match scoring exactly the threshold counts
  EXPECT_NEAR(evaluate_breakdown(gt, dets, kTwoClasses, options).agnostic.recall_at_score, 1.0, kTight);
  // The first box is 2 px off (IoU 48/52 = 0.92): COCO's thresholds above 0.92 miss it,
  // so class-agnostic AP@[.5:.95] is below 1 though AP@0.5 is 1.
  EXPECT_NEAR(at_03.agnostic.ap50, 1.0, kTight);
  EXPECT_LT(at_03.agnostic_coco_ap, 1.0);
  EXPECT_GT(at_03.agnostic_coco_ap, 0.5);
}

TEST(EvalDetBreakdown, RejectsMisuse) {
  const std::vector<std::vector<TruthBox>> gt = {{truth(1, 0, 0, 10, 10)}};
  EXPECT_THROW(evaluate_breakdown(gt, {}, kTwoClasses), std::invalid_argument);
  EXPECT_THROW(evaluate_breakdown(gt, {{detected(3, 0, 0, 10, 10, 0.5)}}, kTwoClasses), std::invalid_argument);
}

}  // namespace
}  // namespace flexsight

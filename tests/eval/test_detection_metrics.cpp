// evaluate_detections (host/eval/detection_metrics.h) on cases small enough to work out by
// hand; the comparison with pycocotools on larger random cases is
// tests/eval/eval_det_pycocotools_check.py.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "host/eval/detection_metrics.h"
#include "host/eval/detection_results_reader.h"
#include "host/io/input_error.h"
#include "tests/eval/detection_boxes.h"

namespace flexsight {
namespace {

using namespace detection_boxes;

// The COCO AP of one class whose envelope is `high` up to recall `reach` (a multiple of
// 0.01) and `low` beyond, up to recall 1: the 101 recall points 0, 0.01, ..., 1 split
// into those <= reach and the rest.
double coco_two_level(double high, int points_at_high, double low) {
  return (points_at_high * high + (101 - points_at_high) * low) / 101;
}

TEST(EvalDetMetrics, BoxIouIsPycocotoolsBbIou) {
  // [0,0,10,10] and [5,0,10,10]: intersection 5 x 10 = 50, union 100 + 100 - 50.
  EXPECT_NEAR(box_iou({0, 0, 10, 10}, {5, 0, 10, 10}), 50.0 / 150.0, kTight);
  // A crowd region divides by the detection's own area: 50 / 100.
  EXPECT_NEAR(box_iou({0, 0, 10, 10}, {5, 0, 10, 10}, true), 0.5, kTight);
  // No "+1": boxes that touch share no pixel.
  EXPECT_EQ(box_iou({0, 0, 10, 10}, {10, 0, 10, 10}), 0.0);
  EXPECT_EQ(box_iou({0, 0, 10, 10}, {0, 20, 10, 10}), 0.0);
  EXPECT_EQ(box_iou({2, 3, 7, 5}, {2, 3, 7, 5}), 1.0);
}

TEST(EvalDetMetrics, PerfectDetectionsScoreOne) {
  const std::vector<std::vector<TruthBox>> gt = {
      {truth(1, 0, 0, 10, 10), truth(2, 20, 5, 8, 12)},
      {truth(1, 3, 4, 30, 20)},
  };
  const std::vector<std::vector<DetectedBox>> found = {
      {detected(2, 20, 5, 8, 12, 0.4), detected(1, 0, 0, 10, 10, 0.9)},
      {detected(1, 3, 4, 30, 20, 0.2)},
  };
  const DetectionScores s = evaluate_detections(gt, found, kTwoClasses);
  EXPECT_EQ(s.map50, 1.0);
  // COCO's precision is TP / (TP + FP + 2^-52): 1 / (1 + 2^-52), one ulp below 1.
  EXPECT_NEAR(s.map50_95, 1.0, kTight);
  EXPECT_NEAR(s.ap50_coco, 1.0, kTight);
  EXPECT_NEAR(s.ap75, 1.0, kTight);
  EXPECT_EQ(s.images, 2);
  EXPECT_EQ(s.ground_truth, 3);
  EXPECT_EQ(s.detections, 3);
  ASSERT_EQ(s.classes.size(), 2u);
  EXPECT_EQ(s.classes[0].ground_truth, 2);
  EXPECT_EQ(s.classes[1].detections, 1);
  for (double p : s.mean_precision_101) EXPECT_EQ(p, 1.0);
}

TEST(EvalDetMetrics, FalsePositiveRankedFirst) {
  // Two objects; the best-scored detection is wrong. VOC points (recall, precision):
  // (0, 0), (1/2, 1/2), (1, 2/3); envelope 2/3 everywhere: AP = 2/3. COCO: the same
  // envelope at all 101 recall points (exact boxes pass every IoU threshold): 2/3.
  const std::vector<std::vector<TruthBox>> gt = {{truth(1, 0, 0, 10, 10), truth(1, 40, 0, 10, 10)}};
  const std::vector<std::vector<DetectedBox>> found = {{detected(1, 0, 0, 10, 10, 0.8),
                                                        detected(1, 20, 30, 10, 10, 0.9),
                                                        detected(1, 40, 0, 10, 10, 0.7)}};
  const DetectionScores s = evaluate_detections(gt, found, {{1, "one"}});
  EXPECT_NEAR(s.map50, 2.0 / 3.0, kTight);
  EXPECT_NEAR(s.map50_95, 2.0 / 3.0, kTight);
  EXPECT_NEAR(s.ap50_coco, 2.0 / 3.0, kTight);
  EXPECT_NEAR(s.ap75, 2.0 / 3.0, kTight);
  const PrCurve& curve = s.classes[0].curve;
  ASSERT_EQ(curve.recall.size(), 3u);
  EXPECT_EQ(curve.recall[0], 0.0);
  EXPECT_EQ(curve.recall[1], 0.5);
  EXPECT_EQ(curve.recall[2], 1.0);
  for (double p : curve.precision) EXPECT_NEAR(p, 2.0 / 3.0, kTight);
  EXPECT_NEAR(s.mean_precision_101.front(), 2.0 / 3.0, kTight);
  EXPECT_NEAR(s.mean_precision_101.back(), 2.0 / 3.0, kTight);
}

TEST(EvalDetMetrics, DuplicateIsAFalsePositive) {
  // Object A found twice before object B. VOC: (1/2, 1), (1/2, 1/2), (1, 2/3); envelope
  // 1 up to recall 1/2, 2/3 beyond: AP = 1/2 + 1/2 * 2/3 = 5/6. COCO samples the envelope
  // at 0, 0.01, ..., 1: 1 at the 51 points up to 0.5, 2/3 at the other 50.
  const std::vector<std::vector<TruthBox>> gt = {{truth(1, 0, 0, 10, 10), truth(1, 40, 0, 10, 10)}};
  const std::vector<std::vector<DetectedBox>> found = {{detected(1, 0, 0, 10, 10, 0.9),
                                                        detected(1, 1, 0, 10, 10, 0.8),
                                                        detected(1, 40, 0, 10, 10, 0.7)}};
  const DetectionScores s = evaluate_detections(gt, found, {{1, "one"}});
  EXPECT_NEAR(s.map50, 5.0 / 6.0, kTight);
  EXPECT_NEAR(s.ap50_coco, coco_two_level(1.0, 51, 2.0 / 3.0), kTight);
  // The duplicate overlaps A with IoU 9 x 10 / (200 - 90) = 0.818: it is matched to
  // nothing at every threshold, so every threshold gives the same AP.
  EXPECT_NEAR(s.map50_95, coco_two_level(1.0, 51, 2.0 / 3.0), kTight);
  EXPECT_NEAR(s.ap75, coco_two_level(1.0, 51, 2.0 / 3.0), kTight);
}

TEST(EvalDetMetrics, TwoClassesAndTheIouThresholds) {
  // Class 1 exact (AP 1 everywhere). Class 2: one box found with IoU 0.72 (10 x 7.2 of a
  // 10 x 10 box): a match at the COCO thresholds 0.50 ... 0.70, none at 0.75 ... 0.95, so
  // its COCO AP is 5/10, AP50 1, AP75 0.
  const std::vector<std::vector<TruthBox>> gt = {{truth(1, 0, 0, 10, 10)}, {truth(2, 0, 0, 10, 10)}};
  const std::vector<std::vector<DetectedBox>> found = {{detected(1, 0, 0, 10, 10, 0.5)},
                                                       {detected(2, 0, 0, 10, 7.2, 0.5)}};
  DetectionEvalOptions options;
  options.iou_threshold = 0.75;
  const DetectionScores s = evaluate_detections(gt, found, kTwoClasses, options);
  EXPECT_EQ(s.map50, 1.0);
  EXPECT_NEAR(s.map50_95, (1.0 + 0.5) / 2, kTight);
  EXPECT_NEAR(s.ap50_coco, 1.0, kTight);
  EXPECT_NEAR(s.ap75, (1.0 + 0.0) / 2, kTight);
  EXPECT_NEAR(s.classes[1].coco_ap, 0.5, kTight);
  // VOC at 0.75: class 2's detection misses.
  EXPECT_EQ(s.classes[1].voc_ap50, 1.0);
  EXPECT_EQ(s.classes[1].voc_ap, 0.0);
  EXPECT_NEAR(s.map, 0.5, kTight);
}

TEST(EvalDetMetrics, ClassWithoutGroundTruthEntersNoMean) {
  const std::vector<std::vector<TruthBox>> gt = {{truth(1, 0, 0, 10, 10)}};
  const std::vector<std::vector<DetectedBox>> found = {
      {detected(1, 0, 0, 10, 10, 0.5), detected(2, 30, 30, 10, 10, 0.9)}};
  const DetectionScores s = evaluate_detections(gt, found, kTwoClasses);
  EXPECT_EQ(s.classes_with_ground_truth, 1);
  EXPECT_EQ(s.map50, 1.0);
  EXPECT_NEAR(s.map50_95, 1.0, kTight);
  EXPECT_EQ(s.classes[1].detections, 1);
  EXPECT_TRUE(std::isnan(s.classes[1].voc_ap50));
  EXPECT_TRUE(std::isnan(s.classes[1].coco_ap));
}

TEST(EvalDetMetrics, NoDetectionsScoreZero) {
  const std::vector<std::vector<TruthBox>> gt = {{truth(1, 0, 0, 10, 10)}, {truth(2, 5, 5, 10, 10)}};
  const DetectionScores s = evaluate_detections(gt, {{}, {}}, kTwoClasses);
  EXPECT_EQ(s.map50, 0.0);
  EXPECT_EQ(s.map50_95, 0.0);
  EXPECT_EQ(s.ap50_coco, 0.0);
  EXPECT_EQ(s.ap75, 0.0);
  EXPECT_EQ(s.detections, 0);
  for (double p : s.mean_precision_101) EXPECT_EQ(p, 0.0);
}

TEST(EvalDetMetrics, DetectionsOnACrowdRegionAreIgnored) {
  // The best-scored detection lies inside a crowd region (crowd IoU = 1): neither a hit
  // nor a miss. Counted as a false positive, it would halve the AP.
  const std::vector<std::vector<TruthBox>> gt = {
      {truth(1, 0, 0, 10, 10), truth(1, 50, 0, 40, 40, /*crowd=*/true)}};
  const std::vector<std::vector<DetectedBox>> found = {
      {detected(1, 55, 5, 10, 10, 0.9), detected(1, 0, 0, 10, 10, 0.8)}};
  const DetectionScores s = evaluate_detections(gt, found, {{1, "one"}});
  EXPECT_EQ(s.classes[0].ground_truth, 1);
  EXPECT_EQ(s.classes[0].crowd, 1);
  EXPECT_EQ(s.ground_truth, 1);
  EXPECT_EQ(s.map50, 1.0);
  EXPECT_NEAR(s.map50_95, 1.0, kTight);
}

TEST(EvalDetMetrics, EqualIouTiesFollowEachMetricsRule) {
  // A = [0,0,20,20] and B = [12,0,20,20]; D1 = [6,0,20,20] overlaps both by 14 x 20 = 280
  // of 520 (IoU 0.538); D2 = A exactly (IoU 0.25 with B).
  // VOC takes the first of equal IoUs: D1 -> A, then D2 finds A taken, B too far: a
  // false positive. Points (1/2, 1), (1/2, 1/2): AP 1/2.
  // COCOeval takes the later one: D1 -> B, D2 -> A: AP 1 at IoU 0.5. From 0.55 up D1
  // matches nothing (FP first), D2 -> A: points (0, 0), (1/2, 1/2), envelope 1/2 up to
  // recall 0.5, then none: 51 of 101 points at 1/2.
  const std::vector<std::vector<TruthBox>> gt = {{truth(1, 0, 0, 20, 20), truth(1, 12, 0, 20, 20)}};
  const std::vector<std::vector<DetectedBox>> found = {
      {detected(1, 6, 0, 20, 20, 0.9), detected(1, 0, 0, 20, 20, 0.8)}};
  const DetectionScores s = evaluate_detections(gt, found, {{1, "one"}});
  EXPECT_NEAR(s.map50, 0.5, kTight);
  EXPECT_NEAR(s.ap50_coco, 1.0, kTight);
  const double above = coco_two_level(0.5, 51, 0.0);
  EXPECT_NEAR(s.ap75, above, kTight);
  EXPECT_NEAR(s.map50_95, (1.0 + 9 * above) / 10, kTight);
}

TEST(EvalDetMetrics, CocoKeepsTheBestHundredPerImageAndClass) {
  // 100 false positives outscore the one true detection: COCOeval drops it (AP 0); VOC
  // keeps every detection: recall 1 at precision 1/101.
  std::vector<std::vector<DetectedBox>> found(1);
  for (int i = 0; i < 100; ++i) found[0].push_back(detected(1, 100 + i, 100, 5, 5, 0.9));
  found[0].push_back(detected(1, 0, 0, 10, 10, 0.5));
  const std::vector<std::vector<TruthBox>> gt = {{truth(1, 0, 0, 10, 10)}};
  const DetectionScores s = evaluate_detections(gt, found, {{1, "one"}});
  EXPECT_EQ(s.map50_95, 0.0);
  EXPECT_NEAR(s.map50, 1.0 / 101.0, kTight);
  DetectionEvalOptions more;
  more.coco_max_detections = 101;
  EXPECT_GT(evaluate_detections(gt, found, {{1, "one"}}, more).ap50_coco, 0.0);
}

TEST(EvalDetMetrics, TiedScoresRankByImageThenListOrder) {
  // Equal scores: image 0's false positive ranks before image 1's hit. VOC points (0, 0),
  // (1, 1/2): AP 1/2. In the other order it would be 1.
  const std::vector<std::vector<TruthBox>> gt = {{}, {truth(1, 0, 0, 10, 10)}};
  const std::vector<std::vector<DetectedBox>> found = {{detected(1, 50, 50, 10, 10, 0.5)},
                                                       {detected(1, 0, 0, 10, 10, 0.5)}};
  const DetectionScores s = evaluate_detections(gt, found, {{1, "one"}});
  EXPECT_NEAR(s.map50, 0.5, kTight);
  EXPECT_NEAR(s.ap50_coco, 0.5, kTight);  // 101 points of 1/2 (with pycocotools' epsilon)
}

TEST(EvalDetMetrics, RejectsMisuse) {
  const std::vector<std::vector<TruthBox>> gt = {{truth(1, 0, 0, 10, 10)}};
  EXPECT_THROW(evaluate_detections(gt, {}, {{1, "one"}}), std::invalid_argument);
  EXPECT_THROW(evaluate_detections(gt, {{detected(3, 0, 0, 1, 1, 0.5)}}, {{1, "one"}}),
               std::invalid_argument);
  EXPECT_THROW(evaluate_detections(gt, {{}}, {{1, "one"}, {1, "again"}}), std::invalid_argument);
  DetectionEvalOptions options;
  options.iou_threshold = 0;
  EXPECT_THROW(evaluate_detections(gt, {{}}, {{1, "one"}}, options), std::invalid_argument);
}

// The results reader refuses a box no image could hold, naming the file and entry.
TEST(EvalDetResultsReader, RefusesABoxBeyondAMillionPixels) {
  const DetectionGroundTruth truth(std::string(FLEXSIGHT_TEST_DATA_DIR) +
                                   "/detect/tless_synth_8/coco_instances.json");
  const std::string path =
      (std::filesystem::temp_directory_path() / "flexsight_results_huge_box.json").string();
  std::ofstream(path) << R"([{"image_id": 0, "category_id": 14, "bbox": [1, 2, 3, 4], "score": 0.5},
    {"image_id": 0, "category_id": 14, "bbox": [1, 2, 1e308, 4], "score": 0.5}])";
  try {
    read_detection_results(path, truth);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": entry 1: bbox [1,2,1e+308,4] reaches beyond "
                                         "1000000 pixels"),
              std::string::npos)
        << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace flexsight

#include "host/eval/detection_metrics.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "host/eval/coco_box_eval.h"
#include "host/eval/voc_matching.h"

namespace flexsight {
namespace {

constexpr int kCurvePoints = 101;

double mean_of_defined(const std::vector<ClassDetectionScores>& classes,
                       double ClassDetectionScores::*value) {
  double sum = 0;
  int count = 0;
  for (const ClassDetectionScores& scores : classes) {
    if (std::isnan(scores.*value)) continue;
    sum += scores.*value;
    ++count;
  }
  return count ? sum / count : std::nan("");
}

double mean(const std::array<double, coco_eval::kThresholds>& values) {
  double sum = 0;
  for (double value : values) sum += value;
  return sum / values.size();
}

}  // namespace

void DetectionEvalOptions::check() const {
  if (!(iou_threshold > 0 && iou_threshold <= 1)) {
    throw std::invalid_argument("iou_threshold must lie in (0, 1]");
  }
  if (coco_max_detections < 1) throw std::invalid_argument("coco_max_detections must be >= 1");
}

double PrCurve::precision_at(double recall_level) const {
  const auto at = std::lower_bound(recall.begin(), recall.end(), recall_level);
  return at == recall.end() ? 0.0 : precision[static_cast<std::size_t>(at - recall.begin())];
}

double box_iou(const BoxXywh& detection, const BoxXywh& truth, bool truth_is_crowd) {
  // pycocotools' bbIou (maskApi.c), in its order of operations.
  const double detection_area = detection[2] * detection[3];
  const double truth_area = truth[2] * truth[3];
  const double w = std::fmin(detection[2] + detection[0], truth[2] + truth[0]) -
                   std::fmax(detection[0], truth[0]);
  if (w <= 0) return 0;
  const double h = std::fmin(detection[3] + detection[1], truth[3] + truth[1]) -
                   std::fmax(detection[1], truth[1]);
  if (h <= 0) return 0;
  const double intersection = w * h;
  const double united = truth_is_crowd ? detection_area : detection_area + truth_area - intersection;
  return intersection / united;
}

DetectionScores evaluate_detections(const std::vector<std::vector<TruthBox>>& truth,
                                    const std::vector<std::vector<DetectedBox>>& detections,
                                    const std::vector<DetectionCategory>& categories,
                                    const DetectionEvalOptions& options) {
  options.check();
  if (truth.size() != detections.size()) {
    throw std::invalid_argument("evaluate_detections: " + std::to_string(truth.size()) +
                                " images of ground truth but " +
                                std::to_string(detections.size()) + " of detections");
  }
  DetectionScores scores;
  scores.iou_threshold = options.iou_threshold;
  scores.images = static_cast<int>(truth.size());
  scores.classes.resize(categories.size());
  const std::vector<ClassBoxes> boxes = boxes_by_class(truth, detections, categories);

  for (std::size_t c = 0; c < categories.size(); ++c) {
    ClassDetectionScores& result = scores.classes[c];
    result.category_id = categories[c].id;
    result.name = categories[c].name;
    for (const auto& image : boxes[c].truth) {
      for (const TruthBox* box : image) (box->crowd ? result.crowd : result.ground_truth) += 1;
    }
    for (const auto& image : boxes[c].detections) result.detections += static_cast<int>(image.size());
    result.voc_ap50 = voc_match(boxes[c], 0.5).ap;
    VocMatching voc = voc_match(boxes[c], options.iou_threshold);
    result.voc_ap = voc.ap;
    result.curve = std::move(voc.curve);
    const coco_eval::ClassAp coco =
        coco_eval::evaluate_class(boxes[c].truth, boxes[c].detections, options.coco_max_detections);
    const double nan = std::nan("");
    result.coco_ap = coco.defined ? mean(coco.ap) : nan;
    result.coco_ap50 = coco.defined ? coco.ap[0] : nan;
    result.coco_ap75 = coco.defined ? coco.ap[5] : nan;  // thresholds[5] == 0.75
    scores.ground_truth += result.ground_truth;
    scores.detections += result.detections;
    if (result.ground_truth > 0) ++scores.classes_with_ground_truth;
  }
  scores.map50 = mean_of_defined(scores.classes, &ClassDetectionScores::voc_ap50);
  scores.map = mean_of_defined(scores.classes, &ClassDetectionScores::voc_ap);
  scores.map50_95 = mean_of_defined(scores.classes, &ClassDetectionScores::coco_ap);
  scores.ap50_coco = mean_of_defined(scores.classes, &ClassDetectionScores::coco_ap50);
  scores.ap75 = mean_of_defined(scores.classes, &ClassDetectionScores::coco_ap75);

  scores.mean_precision_101.assign(kCurvePoints, 0.0);
  if (scores.classes_with_ground_truth > 0) {
    for (int r = 0; r < kCurvePoints; ++r) {
      const double level = r == kCurvePoints - 1 ? 1.0 : r * (1.0 / 100.0);
      double sum = 0;
      for (const ClassDetectionScores& result : scores.classes) {
        if (result.ground_truth > 0) sum += result.curve.precision_at(level);
      }
      scores.mean_precision_101[r] = sum / scores.classes_with_ground_truth;
    }
  }
  return scores;
}

}  // namespace flexsight

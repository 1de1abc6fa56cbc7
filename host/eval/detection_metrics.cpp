#include "host/eval/detection_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>

#include "host/eval/coco_box_eval.h"

namespace flexsight {
namespace {

constexpr int kCurvePoints = 101;

// One class's boxes, per image.
struct ClassBoxes {
  std::vector<std::vector<const TruthBox*>> truth;
  std::vector<std::vector<const DetectedBox*>> detections;
};

struct VocResult {
  double ap = 0;
  PrCurve curve;
};

// PASCAL VOC 2010+ AP of one class at `threshold`: every detection of the class, best
// score first (ties: image order, then list order), takes the unmatched non-crowd box of
// its image with the highest IoU (the first on ties) when that IoU reaches the threshold
// (a true positive); else it is ignored when it covers a crowd region that much (COCO's
// crowd IoU, as VOC ignores "difficult" objects), and a false positive otherwise. AP is
// the area under the precision envelope (precision made monotone from the right) over
// every recall step.
VocResult voc_class(const ClassBoxes& boxes, double threshold) {
  struct Record {
    double score;
    std::size_t image;
    const DetectedBox* box;
  };
  std::vector<Record> records;
  std::vector<std::vector<std::uint8_t>> used(boxes.truth.size());
  int positives = 0;
  for (std::size_t i = 0; i < boxes.truth.size(); ++i) {
    used[i].assign(boxes.truth[i].size(), 0);
    for (const TruthBox* truth : boxes.truth[i]) positives += truth->crowd ? 0 : 1;
    for (const DetectedBox* box : boxes.detections[i]) records.push_back({box->score, i, box});
  }
  std::stable_sort(records.begin(), records.end(),
                   [](const Record& a, const Record& b) { return a.score > b.score; });
  VocResult result;
  if (positives == 0) {
    result.ap = std::nan("");
    return result;
  }
  double tp = 0, fp = 0;
  for (const Record& record : records) {
    const std::vector<const TruthBox*>& truth = boxes.truth[record.image];
    int best = -1;
    double best_iou = -1;
    bool on_crowd = false;
    for (std::size_t g = 0; g < truth.size(); ++g) {
      if (truth[g]->crowd) {
        on_crowd = on_crowd || box_iou(record.box->bbox, truth[g]->bbox, true) >= threshold;
        continue;
      }
      if (used[record.image][g]) continue;
      const double iou = box_iou(record.box->bbox, truth[g]->bbox);
      if (iou > best_iou) {
        best_iou = iou;
        best = static_cast<int>(g);
      }
    }
    if (best >= 0 && best_iou >= threshold) {
      used[record.image][best] = 1;
      tp += 1;
    } else if (on_crowd) {
      continue;
    } else {
      fp += 1;
    }
    result.curve.recall.push_back(tp / positives);
    result.curve.precision.push_back(tp / (tp + fp));
  }
  // Envelope, then the area under it: recall steps from 0 to the last point's recall
  // (beyond it the envelope is 0).
  std::vector<double>& precision = result.curve.precision;
  for (std::size_t k = precision.size(); k-- > 1;) {
    precision[k - 1] = std::max(precision[k - 1], precision[k]);
  }
  double previous_recall = 0;
  for (std::size_t k = 0; k < precision.size(); ++k) {
    result.ap += (result.curve.recall[k] - previous_recall) * precision[k];
    previous_recall = result.curve.recall[k];
  }
  return result;
}

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

namespace {

// Every box sorted into its class, keeping image order and order within the image; the
// classes' box counts are added to `scores`.
std::vector<ClassBoxes> boxes_by_class(const std::vector<std::vector<TruthBox>>& truth,
                                       const std::vector<std::vector<DetectedBox>>& detections,
                                       const std::vector<DetectionCategory>& categories,
                                       DetectionScores& scores) {
  std::map<int, std::size_t> class_of_id;
  std::vector<ClassBoxes> boxes(categories.size());
  for (std::size_t c = 0; c < categories.size(); ++c) {
    if (!class_of_id.emplace(categories[c].id, c).second) {
      throw std::invalid_argument("evaluate_detections: category " +
                                  std::to_string(categories[c].id) + " is listed twice");
    }
    boxes[c].truth.resize(truth.size());
    boxes[c].detections.resize(truth.size());
  }
  const auto class_index = [&](int category_id) {
    const auto found = class_of_id.find(category_id);
    if (found == class_of_id.end()) {
      throw std::invalid_argument("evaluate_detections: a box of category " +
                                  std::to_string(category_id) + ", which is not listed");
    }
    return found->second;
  };
  for (std::size_t i = 0; i < truth.size(); ++i) {
    for (const TruthBox& box : truth[i]) {
      const std::size_t c = class_index(box.category_id);
      boxes[c].truth[i].push_back(&box);
      (box.crowd ? scores.classes[c].crowd : scores.classes[c].ground_truth) += 1;
    }
    for (const DetectedBox& box : detections[i]) {
      const std::size_t c = class_index(box.category_id);
      boxes[c].detections[i].push_back(&box);
      scores.classes[c].detections += 1;
    }
  }
  return boxes;
}

}  // namespace

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
  const std::vector<ClassBoxes> boxes = boxes_by_class(truth, detections, categories, scores);

  for (std::size_t c = 0; c < categories.size(); ++c) {
    ClassDetectionScores& result = scores.classes[c];
    result.category_id = categories[c].id;
    result.name = categories[c].name;
    result.voc_ap50 = voc_class(boxes[c], 0.5).ap;
    VocResult voc = voc_class(boxes[c], options.iou_threshold);
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

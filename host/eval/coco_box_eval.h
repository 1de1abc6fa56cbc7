#pragma once
// COCOeval's bounding-box evaluation (pycocotools 2.0.11, cocoeval.py: evaluateImg and
// accumulate with iouType "bbox", area range "all", maxDets 100) for one class, step for
// step, so that the numbers agree with pycocotools' to rounding. Part of
// evaluate_detections (detection_metrics.h); separate because it follows another
// program's code rather than a definition of ours.
#include <array>
#include <vector>

#include "host/eval/detection_metrics.h"

namespace flexsight::coco_eval {

// COCOeval's IoU thresholds, np.linspace(.5, .95, 10) computed as NumPy does.
constexpr int kThresholds = 10;
std::array<double, kThresholds> iou_thresholds();

struct ClassAp {
  // False when the class has no ground truth that is not ignored (pycocotools leaves its
  // precision at -1 and the means skip it).
  bool defined = false;
  // Mean over the 101 recall points of the interpolated precision, per IoU threshold.
  std::array<double, kThresholds> ap{};
};

// One class: `truth[i]` and `detections[i]` are image i's boxes of that class, images in
// ascending COCO id (the order of COCOeval's imgIds), detections in file order.
ClassAp evaluate_class(const std::vector<std::vector<const TruthBox*>>& truth,
                       const std::vector<std::vector<const DetectedBox*>>& detections,
                       int max_detections);

}  // namespace flexsight::coco_eval

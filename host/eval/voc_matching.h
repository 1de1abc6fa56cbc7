#pragma once
// PASCAL VOC's greedy matching of one class's detections to its ground truth, and the
// all-point AP over it (detection_metrics.h's VOC figures). Optionally restricted to
// boxes of one size, as COCO restricts its area ranges: ground truth of other sizes and
// the unmatched detections of other sizes are ignored, neither positive nor negative.
#include <limits>
#include <vector>

#include "host/eval/detection_metrics.h"

namespace flexsight {

// A box's size: sqrt(width x height) in pixels, the side of the square of its area.
double box_size_px(const BoxXywh& box);

// Boxes whose size (box_size_px) lies in [min_px, max_px).
struct SizeRange {
  double min_px = 0;
  double max_px = std::numeric_limits<double>::infinity();
  bool contains(const BoxXywh& box) const;
};

// One class's boxes, per image (images in the same order in both lists).
struct ClassBoxes {
  std::vector<std::vector<const TruthBox*>> truth;
  std::vector<std::vector<const DetectedBox*>> detections;
};

// Every box sorted into its class (the order of `categories`), keeping image order and
// order within the image. Throws std::invalid_argument for a category listed twice or a
// box of a category not listed.
std::vector<ClassBoxes> boxes_by_class(const std::vector<std::vector<TruthBox>>& truth,
                                       const std::vector<std::vector<DetectedBox>>& detections,
                                       const std::vector<DetectionCategory>& categories);

struct VocMatching {
  double ap = 0;     // NaN without positives
  int positives = 0;  // non-crowd ground truth in the size range
  PrCurve curve;
  // The score of the detection that matched each matched positive, best first: the
  // recall above score s is the count of these >= s over `positives`.
  std::vector<double> match_scores;
  // The positives matched by a detection scoring at least `min_score`.
  int matched_from(double min_score) const;
};

// Every detection, best score first (ties: image order, then list order), takes the
// unmatched non-crowd box of its image with the highest IoU (the first on ties) when that
// IoU reaches `threshold`: a true positive when that box is in `range`, else ignored.
// Unmatched, it is ignored when it covers a crowd region that much (COCO's crowd IoU, as
// VOC ignores "difficult" objects) or is itself outside `range`, and a false positive
// otherwise. AP is the area under the precision envelope (precision made monotone from
// the right) over every recall step.
VocMatching voc_match(const ClassBoxes& boxes, double threshold, const SizeRange& range = {});

}  // namespace flexsight

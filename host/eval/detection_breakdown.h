#pragma once
// Beside the per-class APs of evaluate_detections (detection_metrics.h): are the parts
// found at all, whatever they are called (class-agnostic AP: every box one class), and
// how that depends on a part's size in the image (AP and recall per size bin). The
// detector's errors split into missing a part and misnaming it; these figures say which.
#include <string>
#include <vector>

#include "host/eval/detection_metrics.h"
#include "host/eval/voc_matching.h"

namespace flexsight {

struct SizeBin {
  std::string label;  // "<32", "32-64", ...
  SizeRange range;    // of box_size_px: sqrt(width x height) of the ground-truth box
};

// sqrt(area) below 32, 32-64, 64-128 and from 128 pixels (COCO's small / medium / large
// split at 32 and 96 px, with its large range halved: our parts are rarely below 32).
std::vector<SizeBin> default_size_bins();

// Matching at IoU 0.5 (VOC's greedy matching, voc_matching.h), per class or with every
// box one class. Fractions in [0, 1]; NaN where there is no ground truth.
struct MatchFigures {
  int ground_truth = 0;  // non-crowd boxes (of the bin)
  // Per class: the mean over the classes with ground truth (in the bin) of their VOC
  // AP@0.5; class-agnostic: the VOC AP@0.5 of all boxes as one class.
  double ap50 = 0;
  double recall_at_score = 0;  // share of the ground truth matched by a detection scoring >= recall_score
  double recall_any = 0;       // ... by any detection given
};

struct SizeFigures {
  SizeBin bin;
  MatchFigures per_class;  // a match needs the right class
  MatchFigures agnostic;   // any class matches
};

struct DetectionBreakdownOptions {
  // The score of the recall "at the operating point" (detect's and pick's default --score
  // is 0.3); recall at any score is reported too.
  double recall_score = 0.3;
  std::vector<SizeBin> bins = default_size_bins();
  int coco_max_detections = 100;  // per image, all classes together (COCOeval's maxDets)
};

struct DetectionBreakdown {
  double recall_score = 0.3;
  MatchFigures per_class;  // all sizes
  MatchFigures agnostic;   // all sizes
  // COCOeval's AP@[.5:.95] with every box one category (its useCats = 0).
  double agnostic_coco_ap = 0;
  std::vector<SizeFigures> sizes;  // in the order of options.bins
};

// `truth` and `detections` as for evaluate_detections (same checks). A size bin holds the
// ground truth whose box_size_px lies in its range; in it, a detection matched to a box
// of another size is ignored, and an unmatched one counts as a false positive only when
// its own size lies in the range (COCO's area ranges, on VOC's matching). Class-agnostic,
// a part found twice under two classes gives one match and one false positive; an
// image's boxes are taken class by class in the order of `categories` (ties in score or
// IoU fall as in COCOeval with useCats = 0 when the categories ascend).
DetectionBreakdown evaluate_breakdown(const std::vector<std::vector<TruthBox>>& truth,
                                      const std::vector<std::vector<DetectedBox>>& detections,
                                      const std::vector<DetectionCategory>& categories,
                                      const DetectionBreakdownOptions& options = {});

}  // namespace flexsight

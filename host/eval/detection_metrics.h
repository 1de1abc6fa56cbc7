#pragma once
// Scores of an object detector against ground-truth boxes: PASCAL VOC's all-point AP at
// one IoU threshold and the COCO bounding-box AP of pycocotools' COCOeval, per class and
// averaged. The boxes come in as plain lists per image, so the same function scores
// detections read from a results file and detections a model makes on the spot
// (docs/detect.md, "Evaluating detections", has the exact definitions).
#include <array>
#include <string>
#include <vector>

namespace flexsight {

// A box as COCO writes it: x, y of the top-left corner, width, height, in pixels. IoU is
// computed on these numbers as pycocotools does (no "+1" pixel in widths or areas, which
// the old VOC devkit added), for both metrics.
using BoxXywh = std::array<double, 4>;

struct TruthBox {
  int category_id = 0;
  BoxXywh bbox{};
  // COCO's area (the mask's pixel count in a COCO file; width x height for a BOP box).
  // COCOeval ignores a box whose area lies outside the area range, here [0, 1e10].
  double area = 0;
  // A crowd region (COCO iscrowd): never a positive, and detections on it are ignored.
  bool crowd = false;
};

struct DetectedBox {
  int category_id = 0;
  BoxXywh bbox{};
  double score = 0;  // in [0, 1]; higher ranks first
};

struct DetectionCategory {
  int id = 0;
  std::string name;
};

struct DetectionEvalOptions {
  // The IoU from which a detection matches a ground-truth box in the VOC metric and the
  // precision-recall curves (the COCO thresholds are fixed at 0.50:0.05:0.95). The VOC
  // mAP at 0.5 (map50) is reported whatever this is.
  double iou_threshold = 0.5;
  // Detections per image and class that COCOeval keeps, the best first (its maxDets).
  int coco_max_detections = 100;
  // Throws std::invalid_argument for a threshold outside (0, 1] or a count below 1.
  void check() const;
};

// A precision-recall curve: the points after each detection (VOC ranking, ignored
// detections left out), precision already made monotone from the right (the envelope
// the all-point AP integrates).
struct PrCurve {
  std::vector<double> recall;
  std::vector<double> precision;
  // The envelope at recall r: the best precision at a recall >= r (0 past the last point).
  double precision_at(double recall_level) const;
};

// Every AP is a fraction in [0, 1], or NaN where it is undefined (a class without
// ground truth, which no mean includes).
struct ClassDetectionScores {
  int category_id = 0;
  std::string name;
  int ground_truth = 0;  // boxes that are not crowd regions
  int crowd = 0;
  int detections = 0;
  double voc_ap50 = 0;   // VOC all-point AP at IoU 0.5
  double voc_ap = 0;     // the same at options.iou_threshold
  double coco_ap = 0;    // COCO AP@[.5:.95]
  double coco_ap50 = 0;  // COCO AP at IoU 0.5 (101-point interpolation)
  double coco_ap75 = 0;
  PrCurve curve;  // VOC matching at options.iou_threshold
};

struct DetectionScores {
  double iou_threshold = 0.5;  // options.iou_threshold
  double map50 = 0;            // mean voc_ap50
  double map = 0;              // mean voc_ap (at iou_threshold)
  double map50_95 = 0;         // COCO AP@[.5:.95] as COCOeval's stats[0]
  double ap50_coco = 0;        // stats[1]
  double ap75 = 0;             // stats[2]
  int images = 0;
  int ground_truth = 0;  // non-crowd boxes of every class
  int detections = 0;
  int classes_with_ground_truth = 0;  // the classes the means are over
  std::vector<ClassDetectionScores> classes;  // in the order of `categories`
  // The mean over those classes of each class's envelope at recall 0, 0.01, ..., 1
  // (101 points, COCO's recall grid): the curve drawn as the mean.
  std::vector<double> mean_precision_101;
};

// Scores `detections` against `truth`, both one list per image in the same image order.
// Ties in score rank by image order, then by order within the image's list; pass images
// in ascending COCO image id and detections in file order to reproduce pycocotools' order.
// Every box's category_id must be among `categories` (throws std::invalid_argument
// otherwise, as for lists of different lengths): the readers check user input first.
DetectionScores evaluate_detections(const std::vector<std::vector<TruthBox>>& truth,
                                    const std::vector<std::vector<DetectedBox>>& detections,
                                    const std::vector<DetectionCategory>& categories,
                                    const DetectionEvalOptions& options = {});

// IoU of two boxes as pycocotools' bbIou: intersection over union, or over the
// detection's own area when `truth_is_crowd`; 0 without positive overlap.
double box_iou(const BoxXywh& detection, const BoxXywh& truth, bool truth_is_crowd = false);

}  // namespace flexsight

#pragma once
// The report of a detection evaluation (flexsight eval-det): report.md, Markdown tables
// like the stereo evaluator's, and report.json, the same numbers for scripts.
#include <string>

#include "host/eval/detection_breakdown.h"
#include "host/eval/detection_metrics.h"

namespace flexsight {

struct DetectionReport {
  std::string dataset;            // the COCO file or BOP folder read
  std::string dataset_format;     // "COCO" or "BOP"
  std::string detections;         // where the detections came from (the results file)
  std::string detections_format;  // "COCO results", "BOP results", "empty"
  DetectionScores scores;
  DetectionBreakdown breakdown;  // class-agnostic and by size
};

// One sentence per metric: what is matched, how AP is integrated, what is averaged.
extern const char* const kDetectionConventions;

std::string to_markdown(const DetectionReport& report);
// Keys: dataset, dataset_format, detections_file, detections_format, images,
// ground_truth_boxes, crowd_regions, detections, classes_with_ground_truth,
// iou_threshold, map50, map50_95, ap50_coco, ap75, map_at_iou_threshold, conventions,
// classes (category_id, name, ground_truth, crowd, detections, voc_ap50,
// voc_ap_at_iou_threshold, coco_ap, coco_ap50, coco_ap75) and mean_pr_curve (recall,
// precision: 101 points), class_agnostic (ap50, coco_ap, recall_score, ground_truth,
// recall_at_score, recall_any; per_class: the same with the right class needed) and
// by_size (size_px [min, max or null], label, per_class and class_agnostic: ground_truth,
// ap50, recall_at_score, recall_any). APs are fractions in [0, 1]; null where undefined.
std::string to_json(const DetectionReport& report);

}  // namespace flexsight

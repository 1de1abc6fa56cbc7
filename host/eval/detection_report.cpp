#include "host/eval/detection_report.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "host/eval/json_number.h"
#include "host/io/report_text.h"

namespace flexsight {

const char* const kDetectionConventions =
    "Boxes [x, y, w, h] in pixels, IoU without a +1 pixel (as pycocotools). VOC: per class, "
    "detections of all images best score first, each matched to the unmatched ground truth "
    "of its image with the highest IoU >= the threshold, else a false positive (ignored on a "
    "crowd region); AP = area under the precision envelope over all recall points. COCO: "
    "pycocotools' COCOeval (bbox, IoU 0.50:0.05:0.95, 101 recall points, 100 detections per "
    "image and class, area range all). Means over the classes with ground truth.";

namespace {

int crowd_regions(const DetectionScores& scores) {
  int count = 0;
  for (const ClassDetectionScores& c : scores.classes) count += c.crowd;
  return count;
}

std::string figures_cells(const MatchFigures& f) {
  return " " + fraction_text(f.ap50) + " | " + fraction_text(f.recall_at_score) + " | " +
         fraction_text(f.recall_any) + " |";
}

std::string size_row(const std::string& label, const MatchFigures& per_class, const MatchFigures& agnostic) {
  return "| " + label + " | " + std::to_string(per_class.ground_truth) + " |" + figures_cells(per_class) +
         figures_cells(agnostic) + "\n";
}

std::string breakdown_markdown(const DetectionBreakdown& b) {
  const std::string score = threshold_label(b.recall_score);
  std::string text = "\n## Class-agnostic and by part size\n\n";
  text += "Class-agnostic: every box one class (is the part found, whatever it is called); "
          "class-agnostic AP@[.5:.95] (COCO) " + fraction_text(b.agnostic_coco_ap) + ". Size: "
          "sqrt(width x height) of the ground-truth box in pixels. Recall: the share of the "
          "ground truth matched at IoU 0.5 (VOC matching) by a detection scoring >= " + score +
          ", and by any detection.\n\n";
  text += "| size (px) | ground truth | mAP@0.5 | recall (score >= " + score +
          ") | recall (any score) | class-agnostic AP@0.5 | recall (score >= " + score +
          ") | recall (any score) |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
  text += size_row("all", b.per_class, b.agnostic);
  for (const SizeFigures& size : b.sizes) text += size_row(size.bin.label, size.per_class, size.agnostic);
  return text;
}

nlohmann::ordered_json figures_json(const MatchFigures& f) {
  return {{"ground_truth", f.ground_truth},
          {"ap50", number_or_null(f.ap50)},
          {"recall_at_score", number_or_null(f.recall_at_score)},
          {"recall_any", number_or_null(f.recall_any)}};
}

nlohmann::ordered_json breakdown_json(const DetectionBreakdown& b) {
  nlohmann::ordered_json agnostic = figures_json(b.agnostic);
  agnostic["coco_ap"] = number_or_null(b.agnostic_coco_ap);
  agnostic["recall_score"] = b.recall_score;
  agnostic["per_class"] = figures_json(b.per_class);
  return agnostic;
}

nlohmann::ordered_json by_size_json(const DetectionBreakdown& b) {
  nlohmann::ordered_json sizes = nlohmann::ordered_json::array();
  for (const SizeFigures& size : b.sizes) {
    const SizeRange& r = size.bin.range;
    sizes.push_back({{"label", size.bin.label},
                     {"size_px", {r.min_px, std::isfinite(r.max_px) ? nlohmann::ordered_json(r.max_px) : nullptr}},
                     {"per_class", figures_json(size.per_class)},
                     {"class_agnostic", figures_json(size.agnostic)}});
  }
  return sizes;
}

}  // namespace

std::string to_markdown(const DetectionReport& report) {
  const DetectionScores& s = report.scores;
  const bool other_threshold = s.iou_threshold != 0.5;
  std::string text = "# FlexSight detection evaluation\n\n";
  text += "- Data set: `" + report.dataset + "` (" + report.dataset_format + ", " +
          std::to_string(s.images) + " images, " + std::to_string(s.ground_truth) +
          " ground-truth boxes, " + std::to_string(s.classes_with_ground_truth) +
          " classes with ground truth)\n";
  text += "- Detections: `" + report.detections + "` (" + report.detections_format + ", " +
          std::to_string(s.detections) + " boxes)\n";
  text += std::string("- Conventions: ") + kDetectionConventions + "\n\n";

  text += "## Summary\n\n| metric | value |\n|---|---:|\n";
  text += "| mAP@0.5 (VOC all-point) | " + fraction_text(s.map50) + " |\n";
  text += "| mAP@[.5:.95] (COCO) | " + fraction_text(s.map50_95) + " |\n";
  text += "| AP50 (COCO) | " + fraction_text(s.ap50_coco) + " |\n";
  text += "| AP75 (COCO) | " + fraction_text(s.ap75) + " |\n";
  if (other_threshold) {
    text += "| mAP@" + threshold_label(s.iou_threshold) + " (VOC all-point) | " + fraction_text(s.map) + " |\n";
  }

  text += "\n## Per class\n\n| id | name | ground truth | detections | VOC AP@0.5 |";
  std::string rule = "|---:|---|---:|---:|---:|";
  if (other_threshold) {
    text += " VOC AP@" + threshold_label(s.iou_threshold) + " |";
    rule += "---:|";
  }
  text += " COCO AP | COCO AP50 | COCO AP75 |\n" + rule + "---:|---:|---:|\n";
  for (const ClassDetectionScores& c : s.classes) {
    text += "| " + std::to_string(c.category_id) + " | " + markdown_cell(c.name) + " | " +
            std::to_string(c.ground_truth) + " | " + std::to_string(c.detections) + " | " +
            fraction_text(c.voc_ap50) + " |";
    if (other_threshold) text += " " + fraction_text(c.voc_ap) + " |";
    text += " " + fraction_text(c.coco_ap) + " | " + fraction_text(c.coco_ap50) + " | " + fraction_text(c.coco_ap75) + " |\n";
  }
  text += "\nA class without ground truth shows `-`: it enters no mean.\n";
  text += breakdown_markdown(report.breakdown);
  return text;
}

std::string to_json(const DetectionReport& report) {
  const DetectionScores& s = report.scores;
  nlohmann::ordered_json json;
  json["dataset"] = report.dataset;
  json["dataset_format"] = report.dataset_format;
  json["detections_file"] = report.detections;
  json["detections_format"] = report.detections_format;
  json["images"] = s.images;
  json["ground_truth_boxes"] = s.ground_truth;
  json["crowd_regions"] = crowd_regions(s);
  json["detections"] = s.detections;
  json["classes_with_ground_truth"] = s.classes_with_ground_truth;
  json["iou_threshold"] = s.iou_threshold;
  json["map50"] = number_or_null(s.map50);
  json["map50_95"] = number_or_null(s.map50_95);
  json["ap50_coco"] = number_or_null(s.ap50_coco);
  json["ap75"] = number_or_null(s.ap75);
  json["map_at_iou_threshold"] = number_or_null(s.map);
  json["conventions"] = kDetectionConventions;
  json["classes"] = nlohmann::ordered_json::array();
  for (const ClassDetectionScores& c : s.classes) {
    json["classes"].push_back({{"category_id", c.category_id},
                               {"name", c.name},
                               {"ground_truth", c.ground_truth},
                               {"crowd", c.crowd},
                               {"detections", c.detections},
                               {"voc_ap50", number_or_null(c.voc_ap50)},
                               {"voc_ap_at_iou_threshold", number_or_null(c.voc_ap)},
                               {"coco_ap", number_or_null(c.coco_ap)},
                               {"coco_ap50", number_or_null(c.coco_ap50)},
                               {"coco_ap75", number_or_null(c.coco_ap75)}});
  }
  nlohmann::ordered_json recall = nlohmann::ordered_json::array();
  for (std::size_t r = 0; r < s.mean_precision_101.size(); ++r) {
    recall.push_back(r + 1 == s.mean_precision_101.size() ? 1.0 : r * (1.0 / 100.0));
  }
  json["mean_pr_curve"] = {{"recall", recall}, {"precision", s.mean_precision_101}};
  json["class_agnostic"] = breakdown_json(report.breakdown);
  json["by_size"] = by_size_json(report.breakdown);
  return json.dump(2) + "\n";
}

}  // namespace flexsight

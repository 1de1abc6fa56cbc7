#include "host/eval/detection_breakdown.h"

#include <cmath>
#include <stdexcept>

#include "host/eval/coco_box_eval.h"

namespace flexsight {
namespace {

double share(int part, int whole) { return whole > 0 ? static_cast<double>(part) / whole : std::nan(""); }

// The classes' matchings in `range`, pooled: recall over all their ground truth, AP the
// mean over the classes that have some.
MatchFigures per_class_figures(const std::vector<ClassBoxes>& classes, const SizeRange& range, double recall_score) {
  MatchFigures figures;
  int at_score = 0, any = 0, defined = 0;
  double ap_sum = 0;
  for (const ClassBoxes& boxes : classes) {
    const VocMatching matching = voc_match(boxes, 0.5, range);
    if (matching.positives == 0) continue;
    figures.ground_truth += matching.positives;
    at_score += matching.matched_from(recall_score);
    any += static_cast<int>(matching.match_scores.size());
    ap_sum += matching.ap;
    ++defined;
  }
  figures.ap50 = defined ? ap_sum / defined : std::nan("");
  figures.recall_at_score = share(at_score, figures.ground_truth);
  figures.recall_any = share(any, figures.ground_truth);
  return figures;
}

MatchFigures agnostic_figures(const ClassBoxes& all, const SizeRange& range, double recall_score) {
  const VocMatching matching = voc_match(all, 0.5, range);
  MatchFigures figures;
  figures.ground_truth = matching.positives;
  figures.ap50 = matching.ap;
  figures.recall_at_score = share(matching.matched_from(recall_score), matching.positives);
  figures.recall_any = share(static_cast<int>(matching.match_scores.size()), matching.positives);
  return figures;
}

}  // namespace

std::vector<SizeBin> default_size_bins() {
  const double inf = SizeRange().max_px;
  return {{"<32", {0, 32}}, {"32-64", {32, 64}}, {"64-128", {64, 128}}, {">=128", {128, inf}}};
}

DetectionBreakdown evaluate_breakdown(const std::vector<std::vector<TruthBox>>& truth,
                                      const std::vector<std::vector<DetectedBox>>& detections,
                                      const std::vector<DetectionCategory>& categories,
                                      const DetectionBreakdownOptions& options) {
  if (truth.size() != detections.size()) {
    throw std::invalid_argument("evaluate_breakdown: " + std::to_string(truth.size()) +
                                " images of ground truth but " + std::to_string(detections.size()) +
                                " of detections");
  }
  if (options.coco_max_detections < 1) throw std::invalid_argument("coco_max_detections must be >= 1");
  const std::vector<ClassBoxes> classes = boxes_by_class(truth, detections, categories);
  // Every image's boxes class by class (categories' order), as COCOeval with useCats = 0
  // concatenates them: ties in score and IoU then fall as they do there.
  ClassBoxes all;
  all.truth.resize(truth.size());
  all.detections.resize(truth.size());
  for (const ClassBoxes& boxes : classes) {
    for (std::size_t i = 0; i < truth.size(); ++i) {
      all.truth[i].insert(all.truth[i].end(), boxes.truth[i].begin(), boxes.truth[i].end());
      all.detections[i].insert(all.detections[i].end(), boxes.detections[i].begin(), boxes.detections[i].end());
    }
  }
  DetectionBreakdown result;
  result.recall_score = options.recall_score;
  result.per_class = per_class_figures(classes, SizeRange(), options.recall_score);
  result.agnostic = agnostic_figures(all, SizeRange(), options.recall_score);
  const coco_eval::ClassAp coco = coco_eval::evaluate_class(all.truth, all.detections, options.coco_max_detections);
  double sum = 0;
  for (double ap : coco.ap) sum += ap;
  result.agnostic_coco_ap = coco.defined ? sum / coco.ap.size() : std::nan("");
  for (const SizeBin& bin : options.bins) {
    result.sizes.push_back({bin, per_class_figures(classes, bin.range, options.recall_score),
                            agnostic_figures(all, bin.range, options.recall_score)});
  }
  return result;
}

}  // namespace flexsight

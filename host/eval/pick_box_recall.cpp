#include "host/eval/pick_box_recall.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "host/dataset/bop_reader.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  return inter <= 0.0 ? 0.0 : inter / (a.area() + b.area() - inter);
}

bool any_match(const std::vector<cv::Rect2d>& boxes, const cv::Rect2d& truth) {
  return std::any_of(boxes.begin(), boxes.end(), [&](const cv::Rect2d& b) { return iou(b, truth) >= kBoxRecallIou; });
}

nlohmann::ordered_json counts_json(const BoxRecall& r) {
  auto share = [&](int n) { return r.targets > 0 ? static_cast<double>(n) / r.targets : 0.0; };
  return {{"targets", r.targets},
          {"network", r.network},
          {"network_confident", r.network_confident},
          {"depth", r.depth},
          {"merged", r.merged},
          {"merged_confident", r.merged_confident},
          {"recall", {{"network", share(r.network)},
                      {"network_confident", share(r.network_confident)},
                      {"depth", share(r.depth)},
                      {"merged", share(r.merged)},
                      {"merged_confident", share(r.merged_confident)}}}};
}

}  // namespace

BoxRecall score_box_recall(const std::string& bin, const PickResult& result) {
  const BopReader reader(bin);
  if (reader.size() != 1) throw InputError(bin, "is not a synth-bin folder: it does not hold one image");
  std::vector<cv::Rect2d> network, confident, depth, proposed;
  for (const ObjectDetection& d : result.detections) {
    const cv::Rect2d box(d.box[0], d.box[1], d.box[2] - d.box[0], d.box[3] - d.box[1]);
    network.push_back(box);
    if (d.score >= kConfidentScore) confident.push_back(box);
  }
  for (std::size_t i = 0; i < result.depth.segmentation.regions.size(); ++i) {
    const cv::Rect2d box(result.depth.segmentation.regions[i].box);
    depth.push_back(box);
    if (!result.depth.matched[i]) proposed.push_back(box);
  }
  BoxRecall recall;
  recall.bin = bin;
  for (const PartAnnotation& part : reader.record(0).parts) {
    if (part.visib_fract < kBoxRecallMinVisible || part.bbox_visib.empty()) continue;
    const cv::Rect2d truth(part.bbox_visib.x, part.bbox_visib.y, part.bbox_visib.width, part.bbox_visib.height);
    ++recall.targets;
    const bool by_network = any_match(network, truth), by_confident = any_match(confident, truth);
    const bool by_depth = any_match(depth, truth);
    recall.network += by_network;
    recall.network_confident += by_confident;
    recall.depth += by_depth;
    recall.merged += by_network || any_match(proposed, truth);
    recall.merged_confident += by_confident || by_depth;
  }
  return recall;
}

std::string box_recall_json(const std::vector<BoxRecall>& bins) {
  BoxRecall total;
  nlohmann::ordered_json per_bin = nlohmann::ordered_json::array();
  for (const BoxRecall& r : bins) {
    nlohmann::ordered_json entry = {{"bin", r.bin}};
    entry.update(counts_json(r));
    per_bin.push_back(entry);
    total.targets += r.targets, total.network += r.network, total.network_confident += r.network_confident;
    total.depth += r.depth, total.merged += r.merged, total.merged_confident += r.merged_confident;
  }
  nlohmann::ordered_json document = {
      {"what", "class-agnostic box recall: parts at least half visible (bbox_visib) matched at IoU 0.5"},
      {"confident_score", kConfidentScore},
      {"total", counts_json(total)},
      {"per_bin", per_bin}};
  return document.dump(1) + "\n";
}

}  // namespace flexsight

#include "host/eval/pick_report.h"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "host/eval/json_number.h"
#include "host/io/report_text.h"

namespace flexsight {
namespace {

using Json = nlohmann::ordered_json;

// The report's number with `decimals` digits, "n/a" where it is undefined.
std::string number_cell(double value, int decimals, const std::string& unit = "") {
  return fixed_decimals(value, decimals, "n/a", unit);
}

std::string percent(double fraction) { return number_cell(100.0 * fraction, 1, " %"); }

Json stage_json(const PickStageSeconds& s) {
  Json stages = {{"stereo", s.stereo},   {"depth", s.depth},     {"detection", s.detection},
                 {"pose", s.pose},       {"ranking", s.ranking}, {"total", s.total()}};
  if (s.naming > 0.0) stages["naming"] = s.naming;  // only with a namer (pick's --namer)
  return stages;
}

}  // namespace

void summarize(PickReport& report) {
  long targets = 0, posed = 0, top1 = 0, first_right = 0;
  double to_first = 0.0;
  double bad2 = 0.0, bad2_passive = 0.0;
  int passive_bins = 0;
  PickStageSeconds sum;
  std::vector<std::vector<TruthBox>> truth;
  std::vector<std::vector<DetectedBox>> detections;
  for (const BinPickScore& bin : report.bins) {
    targets += bin.targets_visib50;
    posed += bin.posed_visib50;
    top1 += bin.top1_correct ? 1 : 0;
    first_right += bin.first_pick_correct ? 1 : 0;
    to_first += bin.seconds_to_first_pick;
    bad2 += bin.bad2_pattern;
    if (std::isfinite(bin.bad2_no_pattern)) {
      bad2_passive += bin.bad2_no_pattern;
      ++passive_bins;
    }
    sum.stereo += bin.seconds.stereo;
    sum.depth += bin.seconds.depth;
    sum.detection += bin.seconds.detection;
    sum.pose += bin.seconds.pose;
    sum.ranking += bin.seconds.ranking;
    sum.naming += bin.seconds.naming;
    truth.push_back(bin.truth_boxes);
    detections.push_back(bin.detected_boxes);
  }
  const double n = static_cast<double>(report.bins.size());
  report.pose_recall = targets > 0 ? static_cast<double>(posed) / targets : std::nan("");
  report.top1_correct = top1 / n;
  report.first_pick_correct = first_right / n;
  report.seconds_to_first_pick = to_first / n;
  report.bad2_pattern = bad2 / n;
  report.bad2_no_pattern = passive_bins > 0 ? bad2_passive / passive_bins : std::nan("");
  report.mean_seconds = {sum.stereo / n, sum.depth / n, sum.detection / n, sum.pose / n, sum.ranking / n, sum.naming / n};
  report.seconds_per_bin = report.mean_seconds.total();
  const DetectionScores scores = evaluate_detections(truth, detections, report.categories);
  report.detection_map50 = scores.map50;
  report.detection_coco_ap = scores.map50_95;
}

std::string to_json(const PickReport& report) {
  Json bins = Json::array();
  for (const BinPickScore& bin : report.bins) {
    bins.push_back({{"bin", bin.bin},
                    {"parts", bin.parts},
                    {"targets_visib50", bin.targets_visib50},
                    {"posed_visib50", bin.posed_visib50},
                    {"picks", bin.picks},
                    {"top1_correct", bin.top1_correct},
                    {"top1_obj_id", bin.top1_obj_id},
                    {"top1_add_over_diameter", number_or_null(bin.top1_error_ratio)},
                    {"first_pick_correct", bin.first_pick_correct},
                    {"first_pick_accepted", bin.first_pick_accepted},
                    {"first_pick_obj_id", bin.first_pick_obj_id},
                    {"first_pick_add_over_diameter", number_or_null(bin.first_pick_error_ratio)},
                    {"seconds_to_first_pick", number_or_null(bin.seconds_to_first_pick)},
                    {"bad2_pattern", number_or_null(bin.bad2_pattern)},
                    {"bad2_no_pattern", number_or_null(bin.bad2_no_pattern)},
                    {"seconds", stage_json(bin.seconds)}});
  }
  const Json document = {{"bins_dir", report.bins_dir},
                         {"model", report.model},
                         {"templates", report.templates},
                         {"cad", report.cad},
                         {"stereo", report.stereo_path},
                         {"bins", report.bins.size()},
                         {"pose_recall", number_or_null(report.pose_recall)},
                         {"top1_correct", report.top1_correct},
                         {"first_pick_correct", report.first_pick_correct},
                         {"bad2_pattern", number_or_null(report.bad2_pattern)},
                         {"bad2_no_pattern", number_or_null(report.bad2_no_pattern)},
                         {"detection_map50", number_or_null(report.detection_map50)},
                         {"detection_coco_ap", number_or_null(report.detection_coco_ap)},
                         {"seconds_per_bin", report.seconds_per_bin},
                         {"seconds_to_first_pick", report.seconds_to_first_pick},
                         {"stage_seconds", stage_json(report.mean_seconds)},
                         {"definitions",
                          {{"pose_recall", "parts at least half visible posed within ADD(-S) 0.1 d (BOP matching, the picks as estimates scored by pick_score)"},
                           {"top1_correct", "share of bins whose first-ranked part lies within ADD(-S) 0.1 d of a part of its object"},
                           {"bad2_pattern", "matcher's bad-2 (%) over all pixels with ground truth, with the projector; mean over bins"},
                           {"bad2_no_pattern", "the same on the pair without the pattern (im0_passive.png, im1_passive.png); null when not run"},
                           {"detection_map50", "VOC mAP at IoU 0.5 over the bins; truth: parts at least 10 % visible (less: crowd regions)"},
                           {"seconds_per_bin", "mean of pick's stages, stereo to ranking; the passive matching is not included"},
                           {"first_pick_correct", "share of bins whose first pick (pick's default mode: the first candidate in cheap order passing the acceptance rule, else the best-ranked) lies within ADD(-S) 0.1 d of a part of its object"},
                           {"seconds_to_first_pick", "mean over bins of the time from the pick's start until the first pick is known and every pose begun before it has ended: what pick's default mode takes, ranking aside"}}},
                         {"per_bin", bins}};
  return document.dump(1) + "\n";
}

std::string to_markdown(const PickReport& report) {
  std::ostringstream md;
  md << "# flexsight eval-pick\n\n"
     << "Bins: `" << report.bins_dir << "` (" << report.bins.size() << "); detector `" << report.model
     << "`; stereo on " << report.stereo_path << ".\n\n"
     << "| metric | value |\n|---|---|\n"
     << "| pose recall (parts >= 50 % visible within ADD(-S) 0.1 d) | " << percent(report.pose_recall) << " |\n"
     << "| top-ranked part correct | " << percent(report.top1_correct) << " of bins |\n"
     << "| detection mAP@0.5 | " << percent(report.detection_map50) << " |\n"
     << "| stereo bad-2, with the pattern | " << number_cell(report.bad2_pattern, 2, " %") << " |\n"
     << "| stereo bad-2, without the pattern | " << number_cell(report.bad2_no_pattern, 2, " %") << " |\n"
     << "| first pick correct | " << percent(report.first_pick_correct) << " of bins |\n"
     << "| seconds to the first pick | " << number_cell(report.seconds_to_first_pick, 1) << " |\n"
     << "| seconds per bin | " << number_cell(report.seconds_per_bin, 1) << " |\n\n"
     << "| stage | mean seconds |\n|---|---|\n"
     << "| stereo | " << number_cell(report.mean_seconds.stereo, 2) << " |\n"
     << "| depth | " << number_cell(report.mean_seconds.depth, 2) << " |\n"
     << "| detection | " << number_cell(report.mean_seconds.detection, 2) << " |\n"
     << (report.mean_seconds.naming > 0.0 ? "| naming | " + number_cell(report.mean_seconds.naming, 2) + " |\n" : "")
     << "| pose | " << number_cell(report.mean_seconds.pose, 2) << " |\n"
     << "| ranking | " << number_cell(report.mean_seconds.ranking, 3) << " |\n\n"
     << "| bin | parts | >= 50 % visible | posed | picks | top pick | its ADD(-S)/d | first pick | to first pick s | bad-2 pattern | bad-2 none | seconds |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const BinPickScore& bin : report.bins) {
    md << "| " << std::filesystem::path(bin.bin).filename().string() << " | " << bin.parts << " | "
       << bin.targets_visib50 << " | " << bin.posed_visib50 << " | " << bin.picks << " | "
       << (bin.top1_obj_id == 0 ? std::string("none") : "obj " + std::to_string(bin.top1_obj_id) + (bin.top1_correct ? " right" : " wrong"))
       << " | " << number_cell(bin.top1_error_ratio, 3) << " | "
       << (bin.first_pick_obj_id == 0 ? std::string("none")
                                      : "obj " + std::to_string(bin.first_pick_obj_id) + (bin.first_pick_correct ? " right" : " wrong") +
                                            (bin.first_pick_accepted ? "" : " (none accepted)"))
       << " | " << number_cell(bin.seconds_to_first_pick, 1) << " | " << number_cell(bin.bad2_pattern, 2) << " | "
       << number_cell(bin.bad2_no_pattern, 2) << " | " << number_cell(bin.seconds.total(), 1) << " |\n";
  }
  return md.str();
}

}  // namespace flexsight

#pragma once
// The report of `flexsight eval-pick`: the bins' scores (pick_scoring.h) added up into
// report.json (for scripts) and report.md (docs/pick.md, "eval-pick", defines each key).
#include <string>
#include <vector>

#include "host/eval/pick_scoring.h"

namespace flexsight {

struct PickReport {
  std::string bins_dir, model, templates, cad, stereo_path;
  std::vector<BinPickScore> bins;
  std::vector<DetectionCategory> categories;  // the detector's classes
  // Summed / averaged over the bins:
  double pose_recall = 0.0;    // posed_visib50 / targets_visib50
  double top1_correct = 0.0;   // share of bins whose first pick is right
  double bad2_pattern = 0.0;   // mean over bins, %
  double bad2_no_pattern = 0.0;  // NaN when not run
  double detection_map50 = 0.0;  // VOC mAP at IoU 0.5 over the bins' boxes
  double detection_coco_ap = 0.0;  // COCO AP@[.5:.95]
  PickStageSeconds mean_seconds;   // per stage, mean over bins
  double seconds_per_bin = 0.0;    // mean pick time (stereo to ranking)
  double first_pick_correct = 0.0;     // share of bins whose first pick is right
  double seconds_to_first_pick = 0.0;  // mean over bins
};

// Fills the sums and means from report.bins (at least one).
void summarize(PickReport& report);
std::string to_json(const PickReport& report);
std::string to_markdown(const PickReport& report);

}  // namespace flexsight

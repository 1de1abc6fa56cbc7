#pragma once
// The report of a pose evaluation (flexsight eval-pose): report.json, the numbers for
// scripts, and report.md, a summary and a table per object.
#include <map>
#include <string>

#include "host/eval/pose_recall.h"

namespace flexsight {

struct PoseReport {
  std::string dataset;      // the BOP folder read
  std::string results;      // the results file
  std::string cad;          // the CAD folder
  std::string models_info;  // the models_info.json
  int images = 0;                   // images evaluated
  int images_skipped_mirrored = 0;  // flipped once: reflected ground truth, left out
  long results_lines = 0;           // estimates in the results file
  PoseEvalSettings settings;
  PoseScores total;
  std::map<int, PoseScores> per_object;
  std::map<int, bool> symmetric;  // per obj_id: ADD-S (true) or ADD
};

// One sentence per rule: targets, matching, thresholds, averages.
extern const char* const kPoseConventions;

std::string to_markdown(const PoseReport& report);
// Keys: dataset, results, cad, models_info, min_visib_fract, add_recall,
// add_recall_visib50, ar, ar_vsd (null without depth), ar_mssd, ar_mspd, ar_definition,
// counts (images, images_skipped_mirrored, results_lines, ground_truth, targets,
// targets_visib50, estimates, estimates_evaluated), recalls (add, mssd, mspd: threshold
// and recall per threshold; vsd per tau), per_object {"obj_id": the same score keys,
// counts and "add_metric": "ADD-S" or "ADD"}, conventions. Recalls are fractions; null
// where undefined (no target).
std::string to_json(const PoseReport& report);

}  // namespace flexsight

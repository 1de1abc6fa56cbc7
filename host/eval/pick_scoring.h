#pragma once
// Scores `flexsight pick` on a simulated bin (a `synth bin` folder: the MiddEval3 files
// and the BOP ground truth): the parts posed, whether the first-ranked part is right,
// the matcher's bad-2 with and without the pattern, and the detections for the mAP.
// `flexsight eval-pick` adds the bins up (pick_report.h).
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "host/eval/detection_metrics.h"
#include "host/eval/pose_scoring.h"
#include "host/pick/pick_session.h"

namespace flexsight {

struct BinPickScore {
  std::string bin;               // the bin's folder
  int parts = 0;                 // ground-truth parts in view
  int targets_visib50 = 0;       // of those, at least half visible
  int posed_visib50 = 0;         // of those, posed within ADD(-S) 0.1 d
  int picks = 0;                 // parts pick ranked
  bool top1_correct = false;     // the first-ranked part is posed within ADD(-S) 0.1 d
  int top1_obj_id = 0;           // 0 without any pick
  double top1_error_ratio = std::numeric_limits<double>::quiet_NaN();  // its ADD(-S) / d
  // The first pick (pick's default mode: the first candidate in cheap order that passes
  // the acceptance rule, else the best-ranked), scored as the top pick is.
  bool first_pick_correct = false;
  bool first_pick_accepted = false;
  int first_pick_obj_id = 0;  // 0 without any pick
  double first_pick_error_ratio = std::numeric_limits<double>::quiet_NaN();
  double seconds_to_first_pick = std::numeric_limits<double>::quiet_NaN();
  double bad2_pattern = std::numeric_limits<double>::quiet_NaN();     // %, all GT pixels
  double bad2_no_pattern = std::numeric_limits<double>::quiet_NaN();  // NaN: not run
  PickStageSeconds seconds;
  // For the detection scores over all bins: the bin's boxes (truth: parts at least 10 %
  // visible; less visible ones are crowd regions, neither found nor missed).
  std::vector<TruthBox> truth_boxes;
  std::vector<DetectedBox> detected_boxes;
};

// The obj_ids the scoring needs models of: every ground-truth part of the bins.
std::set<int> bin_obj_ids(const std::vector<std::string>& bins);
// The same obj_ids, each with the scene_gt.json of the first bin that holds it.
std::map<int, std::string> bin_truth_sources(const std::vector<std::string>& bins);

// `bin`: a synth-bin folder; `result`: pick on its im0.png / im1.png; `no_pattern`: the
// matcher's disparity on its passive pair (empty: not run). InputError naming the file
// for a bin without its ground truth.
BinPickScore score_pick_on_bin(const std::string& bin, const PickResult& result, const cv::Mat& no_pattern_disparity,
                               const PoseScoringModels& models, const std::string& cad,
                               const std::string& models_info);

}  // namespace flexsight

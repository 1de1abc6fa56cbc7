#pragma once
// Which parts pick had a box for, whatever its class (docs/pick.md, "Proposals from
// depth"): of the parts at least half visible in a simulated bin, those whose visible
// box some box overlaps by IoU 0.5: the detector's, the depth segmentation's, and both.
// `flexsight eval-pick --depth-proposals on` writes them to DIR/box_recall.json.
#include <string>
#include <vector>

#include "host/pick/pick_session.h"

namespace flexsight {

struct BoxRecall {
  std::string bin;
  int targets = 0;            // parts at least half visible
  int network = 0;            // found by a detection above pick's --score
  int network_confident = 0;  // by a detection scoring at least kConfidentScore
  int depth = 0;              // by a kept depth region
  int merged = 0;             // by a detection or a depth proposal (what pick poses)
  int merged_confident = 0;   // by a confident detection or a depth region
};

constexpr double kConfidentScore = 0.3;
constexpr double kBoxRecallIou = 0.5;
constexpr double kBoxRecallMinVisible = 0.5;

// `bin`: a synth-bin folder (BOP ground truth); `result`: pick's on it, run with depth
// proposals. InputError naming the bin for missing ground truth.
BoxRecall score_box_recall(const std::string& bin, const PickResult& result);

// The bins and their sum as JSON.
std::string box_recall_json(const std::vector<BoxRecall>& bins);

}  // namespace flexsight

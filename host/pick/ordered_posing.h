#pragma once
// Pose pick's candidates in their cheap order (candidate_order.h), several proposals at
// once (one estimator per thread), and know the first pick as soon as it is decided
// (docs/pick.md, "The first pick first").
//
// The answer does not depend on thread timing nor on the thread count: it is the first
// candidate in cheap order whose best-fitting proposal passes the acceptance rule
// (pick_acceptance.h), decided only once every proposal of that candidate and of every
// candidate before it has been posed. Proposals are taken in cheap order, so the work
// before the answer is the same in every mode; a proposal of a later candidate that is
// in flight when the answer is decided is waited for and left out of the result.
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "host/pick/candidate_order.h"
#include "host/pick/pick_acceptance.h"
#include "host/pick/pick_naming.h"
#include "host/pick/pick_ranking.h"
#include "host/pose/pose_models.h"

namespace flexsight {

enum class PickMode {
  FirstPick,  // stop at the first accepted pick (every proposal when none is accepted)
  All,        // every proposal posed and ranked by pick_score (recall, the whole bin)
  Budget,     // after the first pick, on in cheap order until the budget is spent
};
// "first", "all", "budget".
const char* pick_mode_name(PickMode mode);

// The depth a candidate is posed with and its visibility measured against: an image of
// the scene depth's size and type whose pixels in and around `box` are the ones to use.
// Called once per candidate, on a posing thread, before its first proposal is posed
// (where a full-resolution stereo of the box would plug in). Empty: the scene's depth.
using CandidateDepth = std::function<cv::Mat(const cv::Rect& box, const cv::Mat& scene_depth_mm)>;

struct PosingOptions {
  PickMode mode = PickMode::FirstPick;
  double budget_seconds = 0.0;  // PickMode::Budget: of the whole pick, from `start`
  int threads = 1;
  PoseEstimatorParams pose;
  std::string model_option;  // names the detector in errors (PoseModels::model)
  AcceptanceRule acceptance;
  CandidateOrderWeights weights;
  CandidateDepth depth_for_candidate;
  std::chrono::steady_clock::time_point start;  // the pick's start (before stereo)
};

struct PosingScene {
  const cv::Mat& bgr;       // the image the boxes are in
  const cv::Mat& depth_mm;  // the measured depth, CV_32FC1
  const PinholeCamera& camera;
  double floor_depth_mm = 0.0;
};

// One candidate as pick treated it, in cheap order.
struct CandidateOutcome {
  OrderedCandidate candidate;
  bool posed = false;       // every proposal of it posed (and kept in the result)
  int best = -1;            // its best-fitting posed proposal (index into the proposals), -1: none fit
  std::string rejection;    // why its best was not accepted (acceptance_failure); "no pose" when none fit
};

struct PosingOutcome {
  // The posed proposals that a template fits, in proposal order (as ranked by rank_picks).
  std::vector<PickCandidate> posed;
  std::vector<CandidateOutcome> candidates;  // in cheap order
  int first_pick = -1;  // the accepted candidate (index into `candidates`); -1: none accepted
  // From the pick's start to when the first pick is known and every pose begun before
  // that has ended (what the first-pick mode waits for); with none accepted, to the end
  // of posing.
  double seconds_to_first_pick = 0.0;
};

// The proposals (pick_session's list: network, named or depth boxes) grouped into
// candidates, ordered by their cheap cues, and posed in that order as `options.mode` says.
PosingOutcome pose_in_cheap_order(const PosingScene& scene, const std::vector<NamedProposal>& proposals,
                                  const PoseModels& models, const PosingOptions& options);

}  // namespace flexsight

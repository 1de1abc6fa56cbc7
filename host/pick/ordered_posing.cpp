#include "host/pick/ordered_posing.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <memory>
#include <mutex>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

using Clock = std::chrono::steady_clock;

// Pixels of a part nearer than this to a nearer measured surface still count as seen:
// stereo depth is a few millimetres off at a metre.
constexpr double kVisibilityToleranceMm = 5.0;
// Proposal boxes overlapping more than this are one part proposed as several classes:
// one candidate (pick_session's duplicate rule).
constexpr double kSamePartIou = 0.5;

cv::Rect proposal_box(const ObjectDetection& d, const cv::Rect& image_rect) {
  return cv::Rect(cv::Point(static_cast<int>(std::floor(d.box[0])), static_cast<int>(std::floor(d.box[1]))),
                  cv::Point(static_cast<int>(std::ceil(d.box[2])), static_cast<int>(std::ceil(d.box[3])))) &
         image_rect;
}

// The proposals grouped into candidates with their cues, in cheap order.
std::vector<OrderedCandidate> ordered_candidates(const PosingScene& scene, const std::vector<NamedProposal>& proposals,
                                                 const CandidateOrderWeights& weights) {
  const cv::Rect image_rect(cv::Point(), scene.bgr.size());
  std::vector<cv::Rect> boxes;
  for (const NamedProposal& p : proposals) boxes.push_back(proposal_box(p.detection, image_rect));
  std::vector<OrderedCandidate> candidates;
  for (std::vector<int>& group : group_overlapping_boxes(boxes, kSamePartIou)) {
    OrderedCandidate c;
    c.box = boxes[group.front()];
    c.cues = depth_cues(scene.depth_mm, c.box, scene.floor_depth_mm);
    for (int i : group) {
      c.cues.detection_score = std::max(c.cues.detection_score, static_cast<double>(proposals[i].detection.score));
      c.cues.naming_score = std::max(c.cues.naming_score, proposals[i].naming_score);
    }
    c.proposals = std::move(group);
    candidates.push_back(std::move(c));
  }
  order_candidates(candidates, weights);
  return candidates;
}

// One proposal posed in its box at `depth_mm`; false when nothing was posed (a box too
// small or without measured depth, or no template of the class fits it).
bool pose_proposal(PoseEstimator& estimator, const PosingScene& scene, const cv::Mat& depth_mm,
                   const NamedProposal& proposal, int index, const PoseModels& models, const PosingOptions& options,
                   PickCandidate& c) {
  const ObjectDetection& d = proposal.detection;
  const cv::Rect box = proposal_box(d, cv::Rect(cv::Point(), scene.bgr.size()));
  if (box.width < 4 || box.height < 4) return false;
  const PoseModel& model = models.model(d.category_id, options.model_option);
  PoseEstimate estimate;
  try {
    estimate = estimator.estimate(model, scene.bgr, depth_mm, scene.camera, box);
  } catch (const InputError&) {
    return false;  // a box without any measured depth: nothing to pose it with
  }
  // No template of the class fits the box at the measured depth: a box of another
  // class, or of several parts; nothing was posed.
  if (estimate.candidates == 0) return false;
  c.obj_id = d.category_id;
  c.pose = estimate.pose;
  c.box = box;
  c.detection_score = d.score;
  c.from_depth = proposal.from_depth;
  c.naming_score = proposal.naming_score;
  c.pose_score = estimate.score;
  c.depth_fit = estimate.depth_fit;
  c.times = estimate.times;
  c.visible_fraction = visible_fraction(model.mesh, estimate.pose, scene.camera, depth_mm, kVisibilityToleranceMm);
  c.height_mm = scene.floor_depth_mm > 0.0 ? scene.floor_depth_mm - estimate.pose.t.z() : 0.0;
  c.pick_score = c.pose_score * c.visible_fraction;
  c.proposal_index = index;
  return true;
}

// The candidate's best-fitting proposal as rank_picks would order them (pick_score, then
// height, then proposal order); -1 when none was posed.
int best_proposal(const OrderedCandidate& candidate, const std::vector<PickCandidate>& results,
                  const std::vector<char>& fitted) {
  int best = -1;
  for (int i : candidate.proposals) {
    if (!fitted[i]) continue;
    if (best < 0 || results[i].pick_score > results[best].pick_score ||
        (results[i].pick_score == results[best].pick_score && results[i].height_mm > results[best].height_mm)) {
      best = i;
    }
  }
  return best;
}

// What the posing threads share: each proposal's pose, which candidates are done, and the
// answer once decided.
struct PosingState {
  std::vector<OrderedCandidate> order;          // the candidates in cheap order
  std::vector<std::pair<int, int>> items;       // the work: (candidate, proposal), in cheap order
  std::vector<PickCandidate> results;           // per proposal
  std::vector<char> fitted;                     // per proposal: a template fit it
  std::vector<double> began, ended;             // per item, seconds from the pick's start; -1: not taken
  std::vector<std::string> rejection;           // per candidate, once done
  std::vector<cv::Mat> depth;                   // per candidate, while it is posed
  std::unique_ptr<std::once_flag[]> depth_once;
  std::mutex mutex;
  std::vector<int> remaining;  // proposals of each candidate not yet posed
  std::vector<char> accepted;  // of the done candidates
  int frontier = 0;            // the first candidate not known to be done and rejected
  std::atomic<int> answer{-1};
  double answer_seconds = 0.0;

  PosingState(std::vector<OrderedCandidate> ordered, std::size_t proposals)
      : order(std::move(ordered)),
        results(proposals),
        fitted(proposals, 0),
        rejection(order.size()),
        depth(order.size()),
        depth_once(std::make_unique<std::once_flag[]>(order.size())),
        accepted(order.size(), 0) {
    for (int k = 0; k < static_cast<int>(order.size()); ++k) {
      for (int i : order[k].proposals) items.emplace_back(k, i);
      remaining.push_back(static_cast<int>(order[k].proposals.size()));
    }
    began.assign(items.size(), -1.0);
    ended.assign(items.size(), -1.0);
  }

  // Candidate `k` is done (under `mutex`): moves the frontier over the rejected ones; the
  // answer is the first accepted one the frontier reaches.
  void finish(int k, const AcceptanceRule& rule, double seconds) {
    const int best = best_proposal(order[k], results, fitted);
    rejection[k] = best < 0 ? "no pose" : acceptance_failure(results[best], rule);
    accepted[k] = rejection[k].empty();
    depth[k].release();
    while (frontier < static_cast<int>(order.size()) && remaining[frontier] == 0 && !accepted[frontier]) ++frontier;
    if (answer < 0 && frontier < static_cast<int>(order.size()) && remaining[frontier] == 0) {
      answer_seconds = seconds;
      answer = frontier;
    }
  }
};

// Poses the items in cheap order on `threads` threads until the mode says stop.
void pose_items(PosingState& state, const PosingScene& scene, const std::vector<NamedProposal>& proposals,
                const PoseModels& models, const PosingOptions& options) {
  const auto seconds_now = [&] { return std::chrono::duration<double>(Clock::now() - options.start).count(); };
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr failure;
#pragma omp parallel num_threads(std::max(1, options.threads))
  {
    PoseEstimator estimator(options.pose);
    while (!failed) {
      const int item = next++;
      if (item >= static_cast<int>(state.items.size())) break;
      const int k = state.items[item].first, i = state.items[item].second;
      const int answer = state.answer;
      if (answer >= 0 && options.mode == PickMode::FirstPick && k > answer) break;
      if (answer >= 0 && options.mode == PickMode::Budget && seconds_now() > options.budget_seconds) break;
      state.began[item] = seconds_now();
      try {
        std::call_once(state.depth_once[k], [&] {
          state.depth[k] = options.depth_for_candidate ? options.depth_for_candidate(state.order[k].box, scene.depth_mm)
                                                       : scene.depth_mm;
        });
        state.fitted[i] = pose_proposal(estimator, scene, state.depth[k], proposals[i], i, models, options, state.results[i]);
        const std::lock_guard<std::mutex> lock(state.mutex);
        state.ended[item] = seconds_now();
        if (--state.remaining[k] == 0) state.finish(k, options.acceptance, state.ended[item]);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(state.mutex);
        if (!failure) failure = std::current_exception();
        failed = true;
      }
    }
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace

const char* pick_mode_name(PickMode mode) {
  switch (mode) {
    case PickMode::All: return "all";
    case PickMode::Budget: return "budget";
    default: return "first";
  }
}

PosingOutcome pose_in_cheap_order(const PosingScene& scene, const std::vector<NamedProposal>& proposals,
                                  const PoseModels& models, const PosingOptions& options) {
  PosingState state(ordered_candidates(scene, proposals, options.weights), proposals.size());
  pose_items(state, scene, proposals, models, options);

  PosingOutcome outcome;
  outcome.first_pick = state.answer;
  const bool stop_at_answer = options.mode == PickMode::FirstPick && outcome.first_pick >= 0;
  std::vector<char> kept(proposals.size(), 0);  // the proposals of the candidates in the result
  for (int k = 0; k < static_cast<int>(state.order.size()); ++k) {
    CandidateOutcome c;
    c.candidate = state.order[k];
    c.posed = state.remaining[k] == 0 && (!stop_at_answer || k <= outcome.first_pick);
    if (c.posed) {
      c.best = best_proposal(state.order[k], state.results, state.fitted);
      c.rejection = state.rejection[k];
      for (int i : c.candidate.proposals) kept[i] = 1;
    }
    outcome.candidates.push_back(std::move(c));
  }
  for (std::size_t i = 0; i < proposals.size(); ++i) {
    if (kept[i] && state.fitted[i]) outcome.posed.push_back(state.results[i]);
  }
  // The first pick is ready when it is decided and every pose begun before has ended.
  double ready = outcome.first_pick >= 0 ? state.answer_seconds : 0.0;
  for (std::size_t j = 0; j < state.items.size(); ++j) {
    const bool before = outcome.first_pick < 0 || state.began[j] < state.answer_seconds;
    if (state.began[j] >= 0.0 && before) ready = std::max(ready, state.ended[j]);
  }
  outcome.seconds_to_first_pick = ready;
  return outcome;
}

}  // namespace flexsight

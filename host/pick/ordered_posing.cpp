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

// What the posing threads share: which candidates are done, and the answer once decided.
struct PosingProgress {
  std::mutex mutex;
  std::vector<int> remaining;  // proposals of each candidate not yet posed
  std::vector<char> accepted;  // of the done candidates
  int frontier = 0;            // the first candidate not known to be done and rejected
  std::atomic<int> answer{-1};
  double answer_seconds = 0.0;

  // Candidate `k` is done: moves the frontier over the rejected ones; the answer is the
  // first accepted one the frontier reaches.
  void finish(int k, bool is_accepted, double seconds) {
    accepted[k] = is_accepted;
    while (frontier < static_cast<int>(remaining.size()) && remaining[frontier] == 0 && !accepted[frontier]) ++frontier;
    if (answer < 0 && frontier < static_cast<int>(remaining.size()) && remaining[frontier] == 0) {
      answer_seconds = seconds;
      answer = frontier;
    }
  }
};

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
  PosingOutcome outcome;
  const std::vector<OrderedCandidate> order = ordered_candidates(scene, proposals, options.weights);
  // The work in cheap order: (candidate, proposal) pairs.
  std::vector<std::pair<int, int>> items;
  for (int k = 0; k < static_cast<int>(order.size()); ++k) {
    for (int i : order[k].proposals) items.emplace_back(k, i);
  }
  const auto seconds_now = [&] { return std::chrono::duration<double>(Clock::now() - options.start).count(); };

  std::vector<PickCandidate> results(proposals.size());
  std::vector<char> fitted(proposals.size(), 0);
  std::vector<double> began(items.size(), -1.0), ended(items.size(), -1.0);
  std::vector<std::string> rejection(order.size());
  std::vector<cv::Mat> candidate_depth(order.size());
  const auto depth_once = std::make_unique<std::once_flag[]>(order.size());
  PosingProgress progress;
  progress.remaining.resize(order.size());
  progress.accepted.assign(order.size(), 0);
  for (int k = 0; k < static_cast<int>(order.size()); ++k) progress.remaining[k] = static_cast<int>(order[k].proposals.size());

  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr failure;
#pragma omp parallel num_threads(std::max(1, options.threads))
  {
    PoseEstimator estimator(options.pose);
    while (!failed) {
      const int item = next++;
      if (item >= static_cast<int>(items.size())) break;
      const auto [k, i] = items[item];
      const int answer = progress.answer;
      if (answer >= 0 && options.mode == PickMode::FirstPick && k > answer) break;
      if (answer >= 0 && options.mode == PickMode::Budget && seconds_now() > options.budget_seconds) break;
      began[item] = seconds_now();
      try {
        std::call_once(depth_once[k], [&] {
          candidate_depth[k] = options.depth_for_candidate ? options.depth_for_candidate(order[k].box, scene.depth_mm)
                                                           : scene.depth_mm;
        });
        fitted[i] = pose_proposal(estimator, scene, candidate_depth[k], proposals[i], i, models, options, results[i]);
        const std::lock_guard<std::mutex> lock(progress.mutex);
        ended[item] = seconds_now();
        if (--progress.remaining[k] == 0) {
          const int best = best_proposal(order[k], results, fitted);
          rejection[k] = best < 0 ? "no pose" : acceptance_failure(results[best], options.acceptance);
          progress.finish(k, rejection[k].empty(), ended[item]);
          candidate_depth[k].release();
        }
      } catch (...) {
        const std::lock_guard<std::mutex> lock(progress.mutex);
        if (!failure) failure = std::current_exception();
        failed = true;
      }
    }
  }
  if (failure) std::rethrow_exception(failure);

  outcome.first_pick = progress.answer;
  const bool stop_at_answer = options.mode == PickMode::FirstPick && outcome.first_pick >= 0;
  for (int k = 0; k < static_cast<int>(order.size()); ++k) {
    CandidateOutcome c;
    c.candidate = order[k];
    c.posed = progress.remaining[k] == 0 && (!stop_at_answer || k <= outcome.first_pick);
    if (c.posed) {
      c.best = best_proposal(order[k], results, fitted);
      c.rejection = rejection[k];
    }
    outcome.candidates.push_back(std::move(c));
  }
  for (int i = 0; i < static_cast<int>(proposals.size()); ++i) {
    if (!fitted[i]) continue;
    const auto in = std::find_if(outcome.candidates.begin(), outcome.candidates.end(), [&](const CandidateOutcome& c) {
      return std::find(c.candidate.proposals.begin(), c.candidate.proposals.end(), i) != c.candidate.proposals.end();
    });
    if (in == outcome.candidates.end() || !in->posed) continue;
    outcome.posed.push_back(results[i]);
  }
  // The first pick is ready when it is decided and every pose begun before has ended.
  double ready = outcome.first_pick >= 0 ? progress.answer_seconds : 0.0;
  for (std::size_t j = 0; j < items.size(); ++j) {
    if (began[j] >= 0.0 && (outcome.first_pick < 0 || began[j] < progress.answer_seconds)) ready = std::max(ready, ended[j]);
  }
  outcome.seconds_to_first_pick = ready;
  return outcome;
}

}  // namespace flexsight

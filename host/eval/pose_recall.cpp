#include "host/eval/pose_recall.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace flexsight {
namespace {

// BOP's MSPD thresholds hold for an image 640 pixels wide and scale with the width;
// dividing the error by width / 640 instead keeps one list of thresholds.
constexpr double kMspdReferenceWidth = 640.0;

// The errors of the kept estimates against the targets of one image and object, per
// metric: errors[e][g] (targets only: other ground truths cannot be matched).
struct GroupErrors {
  std::vector<std::vector<double>> add, mssd, mspd;
  std::vector<std::vector<std::vector<double>>> vsd;  // [tau][e][g]
};

long count_matched(const std::vector<double>& scores, const std::vector<std::vector<double>>& errors,
                   const std::vector<bool>& valid, double threshold) {
  const std::vector<int> matches = match_poses(scores, errors, valid, threshold);
  return std::count_if(matches.begin(), matches.end(), [](int e) { return e >= 0; });
}

void add_matches(RecallCounts& counts, const std::vector<double>& scores,
                 const std::vector<std::vector<double>>& errors, const std::vector<bool>& valid,
                 const std::vector<double>& thresholds, double scale) {
  for (std::size_t k = 0; k < thresholds.size(); ++k) {
    counts.matched[k] += count_matched(scores, errors, valid, thresholds[k] * scale);
  }
}

RecallCounts counts_for(const std::vector<double>& thresholds) {
  RecallCounts counts;
  counts.thresholds = thresholds;
  counts.matched.assign(thresholds.size(), 0);
  return counts;
}

PinholeCamera camera_of(const PoseEvalImage& image) {
  PinholeCamera camera;
  camera.fx = image.K(0, 0);
  camera.fy = image.K(1, 1);
  camera.cx = image.K(0, 2);
  camera.cy = image.K(1, 2);
  camera.width = image.width;
  camera.height = image.height;
  return camera;
}

// The errors of the first `kept` estimates against the targets, with the estimates'
// scores in `scores`; VSD's too when there is a `renderer` (of the model's depth).
GroupErrors group_errors(const PoseEvalImage& image, const PoseErrorModel& model,
                         const std::vector<const TruthInstance*>& targets,
                         const std::vector<const EstimateInstance*>& estimates, std::size_t kept,
                         ModelDepthRenderer* renderer, const PoseEvalSettings& settings,
                         std::vector<double>& scores) {
  GroupErrors errors;
  const bool vsd = renderer != nullptr;
  const double width_scale = kMspdReferenceWidth / image.width;
  std::vector<cv::Mat> truth_depth;
  const PinholeCamera camera = camera_of(image);
  if (vsd) {
    for (const TruthInstance* t : targets) truth_depth.push_back(renderer->depth(t->pose, camera));
    errors.vsd.assign(settings.vsd.taus.size(), {});
  }
  for (std::size_t e = 0; e < kept; ++e) {
    const EstimateInstance& estimate = *estimates[e];
    scores.push_back(estimate.score);
    std::vector<double> add, mssd, mspd;
    std::vector<std::vector<double>> vsd_rows(errors.vsd.size());
    cv::Mat estimate_depth;
    if (vsd) estimate_depth = renderer->depth(estimate.pose, camera);
    for (std::size_t g = 0; g < targets.size(); ++g) {
      const Pose& gt = targets[g]->pose;
      add.push_back(add_or_adds_error(model, estimate.pose, gt));
      mssd.push_back(mssd_error(model, estimate.pose, gt));
      mspd.push_back(mspd_error(model, estimate.pose, gt, image.K) * width_scale);
      if (vsd) {
        const std::vector<double> v =
            vsd_errors(image.depth, estimate_depth, truth_depth[g], image.K, model.diameter(), settings.vsd);
        for (std::size_t k = 0; k < v.size(); ++k) vsd_rows[k].push_back(v[k]);
      }
    }
    errors.add.push_back(add);
    errors.mssd.push_back(mssd);
    errors.mspd.push_back(mspd);
    for (std::size_t k = 0; k < vsd_rows.size(); ++k) errors.vsd[k].push_back(vsd_rows[k]);
  }
  return errors;
}

}  // namespace

std::vector<int> match_poses(const std::vector<double>& scores, const std::vector<std::vector<double>>& errors,
                             const std::vector<bool>& valid, double threshold) {
  std::vector<std::size_t> order(scores.size());
  std::iota(order.begin(), order.end(), 0);
  // Python's sorted(..., reverse=True) is stable: equal scores keep the given order.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return scores[a] > scores[b]; });
  std::vector<int> matched(valid.size(), -1);
  for (std::size_t e : order) {
    int best = -1;
    double best_error = threshold;
    for (std::size_t g = 0; g < valid.size(); ++g) {
      if (!valid[g] || matched[g] >= 0) continue;
      if (errors[e][g] < best_error) {
        best = static_cast<int>(g);
        best_error = errors[e][g];
      }
    }
    if (best >= 0) matched[best] = static_cast<int>(e);
  }
  return matched;
}

std::vector<double> RecallCounts::recalls() const {
  std::vector<double> values;
  for (long m : matched) {
    values.push_back(targets > 0 ? static_cast<double>(m) / static_cast<double>(targets)
                                 : std::numeric_limits<double>::quiet_NaN());
  }
  return values;
}

double RecallCounts::average() const {
  if (targets == 0 || matched.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> values = recalls();
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

double PoseScores::ar_vsd() const {
  return has_vsd ? vsd.average() : std::numeric_limits<double>::quiet_NaN();
}

double PoseScores::ar() const {
  if (has_vsd) return (ar_vsd() + ar_mssd() + ar_mspd()) / 3.0;
  return (ar_mssd() + ar_mspd()) / 2.0;
}

PoseRecallAccumulator::PoseRecallAccumulator(const std::map<int, const PoseErrorModel*>& models,
                                             PoseEvalSettings settings)
    : models_(models), settings_(std::move(settings)) {
  start_counts(total_);
}

PoseRecallAccumulator::~PoseRecallAccumulator() = default;

void PoseRecallAccumulator::start_counts(PoseScores& scores) const {
  scores.add = counts_for({settings_.add_threshold});
  scores.add_visib50 = counts_for({settings_.add_threshold});
  scores.mssd = counts_for(settings_.mssd_thresholds);
  scores.mspd = counts_for(settings_.mspd_thresholds);
  std::vector<double> vsd_thresholds;
  for (std::size_t t = 0; t < settings_.vsd.taus.size(); ++t) {
    vsd_thresholds.insert(vsd_thresholds.end(), settings_.vsd_thresholds.begin(), settings_.vsd_thresholds.end());
  }
  scores.vsd = counts_for(vsd_thresholds);
  scores.has_vsd = vsd_;
}

void PoseRecallAccumulator::add_image(const PoseEvalImage& image) {
  ++images_;
  if (image.depth.empty()) vsd_ = false;
  // Sort the image's instances by object.
  std::map<int, std::vector<const TruthInstance*>> truth;
  std::map<int, std::vector<const EstimateInstance*>> estimates;
  for (const TruthInstance& t : image.truth) truth[t.obj_id].push_back(&t);
  for (const EstimateInstance& e : image.estimates) estimates[e.obj_id].push_back(&e);
  std::vector<int> objects;
  for (const auto& entry : truth) objects.push_back(entry.first);
  for (const auto& entry : estimates) {
    if (!truth.count(entry.first)) objects.push_back(entry.first);
  }
  for (int obj_id : objects) {
    if (!models_.count(obj_id)) {
      throw std::invalid_argument("PoseRecallAccumulator: no model for obj_id " + std::to_string(obj_id));
    }
    if (!per_object_.count(obj_id)) start_counts(per_object_[obj_id]);
    add_group(image, obj_id, truth[obj_id], estimates[obj_id]);
  }
  total_.has_vsd = vsd_;
  for (auto& entry : per_object_) entry.second.has_vsd = vsd_;
}

void PoseRecallAccumulator::add_group(const PoseEvalImage& image, int obj_id,
                                      const std::vector<const TruthInstance*>& truth,
                                      std::vector<const EstimateInstance*> estimates) {
  const PoseErrorModel& model = *models_.at(obj_id);
  const double min_visib50 = std::max(settings_.visib50, settings_.min_visib_fract);
  // The targets, and the stricter ones of the second ADD(-S) recall.
  std::vector<const TruthInstance*> targets;
  std::vector<bool> valid50;
  for (const TruthInstance* t : truth) {
    if (t->visib_fract >= settings_.min_visib_fract) {
      targets.push_back(t);
      valid50.push_back(t->visib_fract >= min_visib50);
    }
  }
  const long target_count = static_cast<long>(targets.size());
  const long target50_count = std::count(valid50.begin(), valid50.end(), true);
  // BOP's n_top = -1: the best-scored estimates, as many as there are targets.
  std::stable_sort(estimates.begin(), estimates.end(),
                   [](const EstimateInstance* a, const EstimateInstance* b) { return a->score > b->score; });
  const std::size_t kept = std::min(estimates.size(), targets.size());

  for (PoseScores* scores : {&total_, &per_object_[obj_id]}) {
    scores->ground_truth += static_cast<long>(truth.size());
    scores->estimates += static_cast<long>(estimates.size());
    scores->estimates_matched_against_targets += static_cast<long>(kept);
    scores->targets += target_count;
    scores->targets_visib50 += target50_count;
    scores->add.targets += target_count;
    scores->add_visib50.targets += target50_count;
    scores->mssd.targets += target_count;
    scores->mspd.targets += target_count;
    scores->vsd.targets += target_count;
  }
  if (kept == 0) return;

  // Errors of each kept estimate against each target.
  const bool vsd = vsd_ && !image.depth.empty();
  ModelDepthRenderer* renderer = nullptr;
  if (vsd) {
    auto& slot = renderers_[obj_id];
    if (!slot) slot = std::make_unique<ModelDepthRenderer>(model.shared_mesh());
    renderer = slot.get();
  }
  std::vector<double> scores;
  const GroupErrors errors = group_errors(image, model, targets, estimates, kept, renderer, settings_, scores);

  // Matches per threshold, into the total and the object's counts.
  const std::vector<bool> all_valid(targets.size(), true);
  const double d = model.diameter();
  const std::size_t kept50 = std::min(kept, static_cast<std::size_t>(target50_count));
  const std::vector<double> scores50(scores.begin(), scores.begin() + static_cast<long>(kept50));
  const std::vector<std::vector<double>> add50(errors.add.begin(), errors.add.begin() + static_cast<long>(kept50));
  for (PoseScores* s : {&total_, &per_object_[obj_id]}) {
    add_matches(s->add, scores, errors.add, all_valid, s->add.thresholds, d);
    add_matches(s->add_visib50, scores50, add50, valid50, s->add_visib50.thresholds, d);
    add_matches(s->mssd, scores, errors.mssd, all_valid, s->mssd.thresholds, d);
    add_matches(s->mspd, scores, errors.mspd, all_valid, s->mspd.thresholds, 1.0);
    if (vsd) {
      const std::size_t per_tau = settings_.vsd_thresholds.size();
      for (std::size_t k = 0; k < errors.vsd.size(); ++k) {
        for (std::size_t j = 0; j < per_tau; ++j) {
          s->vsd.matched[k * per_tau + j] +=
              count_matched(scores, errors.vsd[k], all_valid, settings_.vsd_thresholds[j]);
        }
      }
    }
  }
}

}  // namespace flexsight

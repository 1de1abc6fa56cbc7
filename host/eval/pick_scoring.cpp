#include "host/eval/pick_scoring.h"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "host/dataset/bop_reader.h"
#include "host/eval/metrics.h"
#include "host/eval/pose_errors.h"
#include "host/io/input_error.h"
#include "host/io/middeval3_files.h"
#include "host/io/pfm.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

// Parts less visible than this are no detection targets (BOP's visib_gt_min).
constexpr double kMinVisibleForDetection = 0.1;
constexpr double kAddThreshold = 0.1;  // of the diameter

double bad2_percent(const cv::Mat& disparity, const cv::Mat& truth, const cv::Mat& nonocc) {
  if (disparity.empty()) return std::numeric_limits<double>::quiet_NaN();
  return evaluate_disparity(disparity, truth, nonocc).all.bad_percent[2];
}

Pose truth_pose(const PartAnnotation& part) {
  Pose pose;
  pose.R = part.cam_R_m2c;
  pose.t = part.cam_t_m2c;
  return pose;
}

// The ADD(-S) / d of `pick` to the nearest ground-truth part of its object: NaN when
// the bin holds none (or no model scores it).
double error_ratio(const PickCandidate& pick, const BopImageRecord& record, const PoseScoringModels& models) {
  double best = std::numeric_limits<double>::quiet_NaN();
  const auto model = models.models.find(pick.obj_id);
  for (const PartAnnotation& part : record.parts) {
    if (part.obj_id != pick.obj_id || model == models.models.end()) continue;
    const double ratio = add_or_adds_error(*model->second, pick.pose, truth_pose(part)) / model->second->diameter();
    if (!(ratio >= best)) best = ratio;
  }
  return best;
}

}  // namespace

std::set<int> bin_obj_ids(const std::vector<std::string>& bins) {
  std::set<int> ids;
  for (const std::string& bin : bins) {
    const std::set<int> here = ground_truth_obj_ids(BopReader(bin));
    ids.insert(here.begin(), here.end());
  }
  return ids;
}

std::map<int, std::string> bin_truth_sources(const std::vector<std::string>& bins) {
  std::map<int, std::string> sources;
  for (const std::string& bin : bins) {
    for (const auto& [obj_id, source] : ground_truth_sources(BopReader(bin))) sources.emplace(obj_id, source);
  }
  return sources;
}

BinPickScore score_pick_on_bin(const std::string& bin, const PickResult& result, const cv::Mat& no_pattern_disparity,
                               const PoseScoringModels& models, const std::string& cad,
                               const std::string& models_info) {
  BinPickScore score;
  score.bin = bin;
  score.picks = static_cast<int>(result.picks.size());
  score.seconds = result.seconds;

  const BopReader reader(bin);
  if (reader.size() != 1) throw InputError(bin, "is not a synth-bin folder: it holds " + std::to_string(reader.size()) + " images, not 1");
  const BopImageRecord& record = reader.record(0);
  const BopImageRef ref = reader.ref(0);

  // The parts posed, by BOP's matching (pose_scoring.h): the picks are the estimates.
  PoseScoringInput input;
  input.reader = &reader;
  input.dataset = bin;
  input.image_count = 1;
  input.records_path = bin;
  input.cad = cad;
  input.models_info = models_info;
  input.progress = false;
  for (const PickCandidate& c : result.picks) {
    input.records.push_back(
        pose_estimate_record(ref.scene_id, ref.im_id, c.obj_id, c.pick_score, c.pose.R, c.pose.t));
  }
  const PoseReport report = score_pose_estimates(input, models);
  score.targets_visib50 = static_cast<int>(report.total.add_visib50.targets);
  score.posed_visib50 = report.total.add_visib50.matched.empty() ? 0 : static_cast<int>(report.total.add_visib50.matched[0]);

  // The first-ranked part: right when it lies within 0.1 d of some part of its object.
  if (!result.picks.empty()) {
    score.top1_obj_id = result.picks.front().obj_id;
    score.top1_error_ratio = error_ratio(result.picks.front(), record, models);
    score.top1_correct = score.top1_error_ratio < kAddThreshold;
  }
  // The first pick, the same way.
  score.seconds_to_first_pick = result.seconds_to_first_pick;
  if (result.has_first_pick) {
    score.first_pick_obj_id = result.first_pick.obj_id;
    score.first_pick_accepted = result.first_pick_accepted;
    score.first_pick_error_ratio = error_ratio(result.first_pick, record, models);
    score.first_pick_correct = score.first_pick_error_ratio < kAddThreshold;
  }

  for (const PartAnnotation& part : record.parts) {
    if (part.px_count_visib <= 0) continue;
    ++score.parts;
    TruthBox box;
    box.category_id = part.obj_id;
    const BopBox& b = part.bbox_visib;
    box.bbox = {static_cast<double>(b.x), static_cast<double>(b.y), static_cast<double>(b.width),
                static_cast<double>(b.height)};
    box.area = static_cast<double>(b.width) * b.height;
    box.crowd = part.visib_fract < kMinVisibleForDetection;
    score.truth_boxes.push_back(box);
  }
  for (const ObjectDetection& d : result.detections) {
    score.detected_boxes.push_back(
        {d.category_id, {d.box[0], d.box[1], d.box[2] - d.box[0], d.box[3] - d.box[1]}, d.score});
  }

  const MiddEval3Files files = middeval3_files(bin);
  const cv::Mat truth = read_pfm(files.left_truth);
  const cv::Mat nonocc = cv::imread(files.nonocc_mask, cv::IMREAD_GRAYSCALE);
  if (nonocc.empty()) throw InputError(files.nonocc_mask, "is missing or unreadable");
  if (truth.size() != result.disparity.size() || nonocc.size() != truth.size()) {
    throw InputError(files.left_truth, "is not the size of the bin's images");
  }
  score.bad2_pattern = bad2_percent(result.disparity, truth, nonocc);
  score.bad2_no_pattern = bad2_percent(no_pattern_disparity, truth, nonocc);
  return score;
}

}  // namespace flexsight

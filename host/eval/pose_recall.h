#pragma once
// Recall of pose estimates as the BOP toolkit computes it for the BOP Challenge 2019+
// (scripts/eval_bop19_pose.py over eval_calc_errors.py, pose_matching.py and score.py):
//  * targets: the ground-truth instances at least min_visib_fract visible (BOP: 0.1);
//  * per image and object, only the best-scored estimates count, as many as the object
//    has targets there (BOP's n_top = -1); estimates of an object without a target in
//    the image are ignored;
//  * per error threshold, those estimates, best score first, are each matched to the
//    unmatched target with the smallest error below the threshold (pose_matching.py);
//  * recall = matched targets / targets over the whole data set (or one object), and
//    AR_X = the mean recall over X's thresholds; AR = mean(AR_VSD, AR_MSSD, AR_MSPD).
// Thresholds: ADD(-S) 0.1 d (ADD-S for parts with any symmetry); MSSD 0.05..0.5 d; MSPD
// 5..50 px at an image width of 640 (BOP scales them by width / 640); VSD tau 0.05..0.5
// d times thresholds 0.05..0.5 (100 recalls), delta 15 mm.
#include <Eigen/Core>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "host/eval/pose_errors.h"
#include "host/render/raycaster.h"

namespace flexsight {

struct TruthInstance {
  int obj_id = 0;
  Pose pose;
  double visib_fract = 0.0;
};

struct EstimateInstance {
  int obj_id = 0;
  Pose pose;
  double score = 0.0;
};

// BOP's greedy matching (pose_matching.match_poses) of one image and object: estimates
// in descending score (ties in the given order), each taking the not yet matched valid
// ground truth with the smallest error, if that error is below `threshold` (strictly).
// errors[e][g]: error of estimate e against ground truth g. Returns, per ground truth,
// the index of the estimate matched to it, or -1.
std::vector<int> match_poses(const std::vector<double>& scores, const std::vector<std::vector<double>>& errors,
                             const std::vector<bool>& valid, double threshold);

// Matched targets per threshold, and the number of targets.
struct RecallCounts {
  std::vector<double> thresholds;
  std::vector<long> matched;
  long targets = 0;
  // matched / targets per threshold; NaN without targets.
  std::vector<double> recalls() const;
  // The mean of recalls(): BOP's average recall; NaN without targets.
  double average() const;
};

// The scores of all parts or of one.
struct PoseScores {
  long ground_truth = 0;       // instances in the images evaluated
  long targets = 0;            // of those, at least min_visib_fract visible
  long targets_visib50 = 0;    // at least max(0.5, min_visib_fract) visible
  long estimates = 0;          // estimates given for the images evaluated
  long estimates_matched_against_targets = 0;  // the best-scored ones, as many as targets
  RecallCounts add;            // ADD(-S) at 0.1 d
  RecallCounts add_visib50;    // the same over the targets at least 50 % visible
  RecallCounts mssd, mspd;
  RecallCounts vsd;            // every (tau, threshold) pair, tau major; empty without depth
  bool has_vsd = false;
  double add_recall() const { return add.average(); }
  double add_recall_visib50() const { return add_visib50.average(); }
  double ar_mssd() const { return mssd.average(); }
  double ar_mspd() const { return mspd.average(); }
  double ar_vsd() const;  // NaN without depth
  // mean(AR_VSD, AR_MSSD, AR_MSPD), or mean(AR_MSSD, AR_MSPD) without depth.
  double ar() const;
};

struct PoseEvalSettings {
  // Ground truths less visible than this are no targets (BOP's visib_gt_min).
  double min_visib_fract = 0.1;
  // ADD(-S) threshold, a fraction of the diameter.
  double add_threshold = 0.1;
  // The visibility of the second ADD(-S) recall's targets.
  double visib50 = 0.5;
  std::vector<double> mssd_thresholds = bop_fraction_thresholds();  // fractions of d
  std::vector<double> mspd_thresholds = {5, 10, 15, 20, 25, 30, 35, 40, 45, 50};  // px at 640
  std::vector<double> vsd_thresholds = bop_fraction_thresholds();
  VsdSettings vsd;
};

// One image: its intrinsics and size, its depth (CV_32FC1 mm, empty: no VSD), its
// ground truth and the estimates for it. Poses must be rotations (mirrored images'
// reflected ground truths must be left out by the caller).
struct PoseEvalImage {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  int width = 0, height = 0;
  cv::Mat depth;
  std::vector<TruthInstance> truth;
  std::vector<EstimateInstance> estimates;
};

// Gathers the matches of image after image (so that only one depth image is held at a
// time) and gives the scores at the end.
class PoseRecallAccumulator {
 public:
  // `models` by obj_id; every obj_id of the images' ground truth and estimates must be
  // there (std::invalid_argument otherwise). VSD is computed while every image has a
  // depth; the first image without one turns it off for the whole run.
  PoseRecallAccumulator(const std::map<int, const PoseErrorModel*>& models, PoseEvalSettings settings = {});
  ~PoseRecallAccumulator();

  void add_image(const PoseEvalImage& image);

  const PoseScores& total() const { return total_; }
  // Per obj_id with ground truth or estimates in an image added.
  const std::map<int, PoseScores>& per_object() const { return per_object_; }
  const PoseEvalSettings& settings() const { return settings_; }
  int images() const { return images_; }

 private:
  void add_group(const PoseEvalImage& image, int obj_id, const std::vector<const TruthInstance*>& truth,
                 std::vector<const EstimateInstance*> estimates);
  void start_counts(PoseScores& scores) const;

  std::map<int, const PoseErrorModel*> models_;
  PoseEvalSettings settings_;
  std::map<int, std::unique_ptr<ModelDepthRenderer>> renderers_;
  PoseScores total_;
  std::map<int, PoseScores> per_object_;
  int images_ = 0;
  bool vsd_ = true;
};

}  // namespace flexsight

#pragma once
// Benchmark error metrics, following the MiddEval3 SDK conventions:
// - a pixel is evaluated when its ground truth is finite (and, for the non-occluded
//   set, when the mask says non-occluded);
// - a pixel without a result (non-finite or negative disparity) counts as bad at every
//   threshold;
// - the average absolute error is taken over evaluated pixels that have a result;
// - density is the share of evaluated pixels that have a result.
// Thresholds are in pixels at the resolution of the ground truth given.
#include <array>
#include <opencv2/core.hpp>

namespace flexsight {

inline constexpr std::array<double, 5> kBadThresholds = {0.5, 1.0, 2.0, 3.0, 4.0};

struct ErrorStats {
  std::array<double, 5> bad_percent{};  // per kBadThresholds, in percent
  double avg_error = 0;                 // pixels; NaN when no evaluated pixel has a result
  double density_percent = 0;           // share of evaluated pixels with a result
  long evaluated = 0;                   // number of evaluated pixels
  double bad(double threshold) const;   // throws std::invalid_argument if not in kBadThresholds
};

struct SceneScores {
  ErrorStats nonocc;
  ErrorStats all;
};

// disparity, ground_truth: CV_32FC1 of equal size. nonocc_mask: CV_8UC1, a pixel is
// non-occluded where the mask is 255 (MiddEval3 mask0nocc, Middlebury v2 nonocc.png);
// an empty mask means "every pixel with ground truth is non-occluded" (KITTI noc GT is
// handled by the dataset layer). Throws std::invalid_argument on size/type mismatch.
SceneScores evaluate_disparity(const cv::Mat& disparity, const cv::Mat& ground_truth,
                               const cv::Mat& nonocc_mask);

// Same, restricted further to pixels where `selection` (CV_8UC1) is non-zero; used to
// score only confident pixels.
SceneScores evaluate_disparity(const cv::Mat& disparity, const cv::Mat& ground_truth,
                               const cv::Mat& nonocc_mask, const cv::Mat& selection);

// Unweighted mean of the per-scene statistics (each field averaged over scenes; the
// average error over the scenes that have one, NaN when none has).
ErrorStats average(const std::vector<ErrorStats>& stats);

}  // namespace flexsight

#pragma once
// What a robot cell asks of a stereo result besides bad-N: how good the pixels are that
// pass a confidence threshold (and how many pass), and how far our depth is from the
// depth of the ground-truth disparity through the same calibration, in millimetres.
#include <array>
#include <vector>
#include <opencv2/core.hpp>

#include "host/geometry/stereo_camera.h"

namespace flexsight {

inline constexpr std::array<float, 3> kConfidenceThresholds = {0.25f, 0.5f, 0.75f};
// The threshold of the "confident pixels" depth column.
inline constexpr float kDepthConfidenceThreshold = 0.5f;
// Steps of the sparsification curve: the most confident 5, 10, ..., 100 %.
inline constexpr int kSparsificationSteps = 20;

struct ConfidentStats {
  bool available = false;
  // Over pixels with ground truth: the share with confidence >= threshold, and bad-2
  // (percent) among them.
  std::array<double, kConfidenceThresholds.size()> density_percent{};
  std::array<double, kConfidenceThresholds.size()> bad2_percent{};
  // Sparsification (Hu and Mordohai, 2012): keep the most confident k/20 of the pixels
  // with ground truth, k = 1..20, and average their bad-2 (percent) over the 20 steps.
  // Lower is better; `optimal` ranks by the true error instead, the floor any confidence
  // could reach on this result. Pixels of equal confidence count as one block, kept in
  // proportion where a step cuts through it, so the area does not depend on their order.
  double sparsification_auc_percent = 0;
  double optimal_auc_percent = 0;
  // The curves the areas average: bad-2 (percent) of the most confident k/20, k = 1..20.
  std::array<double, kSparsificationSteps> sparsification_curve_percent{};
  std::array<double, kSparsificationSteps> optimal_curve_percent{};
};

// The bad-2 (percent) of the first k/20 of the pixels ranked by descending `rank`, k =
// 1..20, of `bad` (one flag per pixel); see ConfidentStats. Zeros for no pixels.
std::array<double, kSparsificationSteps> sparsification_curve_percent(
    const std::vector<float>& rank, const std::vector<bool>& bad);
// The mean of that curve: the sparsification area (0 for no pixels).
double sparsification_auc_percent(const std::array<double, kSparsificationSteps>& curve);
double sparsification_auc_percent(const std::vector<float>& rank, const std::vector<bool>& bad);

struct DepthStats {
  bool available = false;
  // Median |Z - Z_gt| in millimetres over pixels with ground truth (a pixel without a
  // result counts as an infinite error), and over those with confidence >=
  // kDepthConfidenceThreshold (NaN without a confidence map or when none passes).
  double median_abs_mm_all = 0;
  double median_abs_mm_confident = 0;
};

// All maps CV_32FC1 of one size; `confidence` may be empty (then unavailable).
ConfidentStats evaluate_confident(const cv::Mat& disparity, const cv::Mat& ground_truth,
                                  const cv::Mat& confidence);

// `camera` sized to the maps. `confidence` may be empty.
DepthStats evaluate_depth(const cv::Mat& disparity, const cv::Mat& ground_truth,
                          const cv::Mat& confidence, const StereoCamera& camera);

}  // namespace flexsight

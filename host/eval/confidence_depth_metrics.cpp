#include "host/eval/confidence_depth_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace flexsight {
namespace {

bool has_result(float d) { return std::isfinite(d) && d >= 0.0f; }

double median(std::vector<double>& values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  if (values.size() % 2 == 1) return values[mid];
  const double upper = values[mid];
  const double lower = *std::max_element(values.begin(), values.begin() + mid);
  return 0.5 * (lower + upper);
}

}  // namespace

std::array<double, kSparsificationSteps> sparsification_curve_percent(
    const std::vector<float>& rank, const std::vector<bool>& bad) {
  CV_Assert(rank.size() == bad.size());
  std::array<double, kSparsificationSteps> curve{};
  const size_t n = rank.size();
  if (n == 0) return curve;
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return rank[a] > rank[b]; });
  size_t kept = 0;        // pixels of the blocks before the current one
  double kept_bad = 0;    // their bad count
  size_t block_end = 0;   // one past the current block of equal rank
  double block_bad = 0;
  for (int k = 1; k <= kSparsificationSteps; ++k) {
    const size_t target =
        std::max<size_t>(1, (n * k + kSparsificationSteps / 2) / kSparsificationSteps);
    // Advance whole blocks until the current one holds the target-th pixel.
    while (block_end < target) {
      kept = block_end;
      kept_bad += block_bad;
      block_bad = 0;
      while (block_end < n && (block_end == kept || rank[order[block_end]] == rank[order[kept]])) {
        block_bad += bad[order[block_end]];
        ++block_end;
      }
    }
    const double from_block = double(target - kept) / double(block_end - kept) * block_bad;
    curve[k - 1] = 100.0 * (kept_bad + from_block) / double(target);
  }
  return curve;
}

double sparsification_auc_percent(const std::array<double, kSparsificationSteps>& curve) {
  double sum = 0;
  for (double value : curve) sum += value;
  return sum / kSparsificationSteps;
}

double sparsification_auc_percent(const std::vector<float>& rank, const std::vector<bool>& bad) {
  return sparsification_auc_percent(sparsification_curve_percent(rank, bad));
}

ConfidentStats evaluate_confident(const cv::Mat& disparity, const cv::Mat& ground_truth,
                                  const cv::Mat& confidence) {
  ConfidentStats stats;
  if (confidence.empty()) return stats;
  CV_Assert(disparity.size() == ground_truth.size() && confidence.size() == disparity.size());
  long known = 0;
  std::array<long, kConfidenceThresholds.size()> passed{}, bad{};
  std::vector<float> ranks, negative_errors;
  std::vector<bool> wrongs;
  for (int y = 0; y < ground_truth.rows; ++y) {
    for (int x = 0; x < ground_truth.cols; ++x) {
      const float truth = ground_truth.at<float>(y, x);
      if (!std::isfinite(truth)) continue;
      ++known;
      const float d = disparity.at<float>(y, x);
      const bool wrong = !has_result(d) || std::abs(d - truth) > 2.0f;
      const float c = confidence.at<float>(y, x);
      ranks.push_back(std::isfinite(c) ? c : -std::numeric_limits<float>::infinity());
      negative_errors.push_back(has_result(d) ? -std::abs(d - truth)
                                              : -std::numeric_limits<float>::infinity());
      wrongs.push_back(wrong);
      for (size_t t = 0; t < kConfidenceThresholds.size(); ++t) {
        if (!(c >= kConfidenceThresholds[t])) continue;
        ++passed[t];
        bad[t] += wrong;
      }
    }
  }
  stats.available = known > 0;
  stats.sparsification_curve_percent = sparsification_curve_percent(ranks, wrongs);
  stats.optimal_curve_percent = sparsification_curve_percent(negative_errors, wrongs);
  stats.sparsification_auc_percent = sparsification_auc_percent(stats.sparsification_curve_percent);
  stats.optimal_auc_percent = sparsification_auc_percent(stats.optimal_curve_percent);
  for (size_t t = 0; t < kConfidenceThresholds.size(); ++t) {
    stats.density_percent[t] = known ? 100.0 * passed[t] / known : 0;
    stats.bad2_percent[t] =
        passed[t] ? 100.0 * bad[t] / passed[t] : std::numeric_limits<double>::quiet_NaN();
  }
  return stats;
}

DepthStats evaluate_depth(const cv::Mat& disparity, const cv::Mat& ground_truth,
                          const cv::Mat& confidence, const StereoCamera& camera) {
  CV_Assert(disparity.size() == ground_truth.size());
  const double to_mm = camera.metres_per_unit * 1e3;
  std::vector<double> all, confident;
  for (int y = 0; y < ground_truth.rows; ++y) {
    for (int x = 0; x < ground_truth.cols; ++x) {
      const float truth = ground_truth.at<float>(y, x);
      if (!std::isfinite(truth)) continue;
      const double z_truth = camera.depth(truth);
      if (!std::isfinite(z_truth)) continue;  // ground truth at infinity: no depth to compare
      const float d = disparity.at<float>(y, x);
      const double z = has_result(d) ? camera.depth(d) : std::numeric_limits<double>::infinity();
      const double error =
          std::isfinite(z) ? std::abs(z - z_truth) * to_mm : std::numeric_limits<double>::infinity();
      all.push_back(error);
      if (!confidence.empty() && confidence.at<float>(y, x) >= kDepthConfidenceThreshold) {
        confident.push_back(error);
      }
    }
  }
  DepthStats stats;
  stats.available = !all.empty();
  stats.median_abs_mm_all = median(all);
  stats.median_abs_mm_confident = median(confident);
  return stats;
}

}  // namespace flexsight

#include "host/eval/metrics.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace flexsight {

namespace {

// Running totals for one region (all or non-occluded). Kept as integer counts so the
// percentages do not depend on summation order.
struct Tally {
  long evaluated = 0;
  long with_result = 0;
  std::array<long, kBadThresholds.size()> bad{};
  double error_sum = 0;  // over evaluated pixels that have a result

  void add(float disparity, float truth) {
    ++evaluated;
    // MiddEval3: a missing result (non-finite or negative) is bad at every threshold
    // and does not enter the average error.
    if (!std::isfinite(disparity) || disparity < 0.0f) {
      for (long& count : bad) ++count;
      return;
    }
    ++with_result;
    const double error = std::fabs(static_cast<double>(disparity) - truth);
    error_sum += error;
    // Strictly greater: an error exactly at the threshold is still good.
    for (std::size_t t = 0; t < kBadThresholds.size(); ++t) {
      if (error > kBadThresholds[t]) ++bad[t];
    }
  }

  // An empty region (no ground truth at all) gives zeros rather than NaN, so reports
  // and JSON stay well formed; `evaluated == 0` tells the reader what happened.
  ErrorStats stats() const {
    ErrorStats result;
    result.evaluated = evaluated;
    if (evaluated == 0) return result;
    for (std::size_t t = 0; t < kBadThresholds.size(); ++t) {
      result.bad_percent[t] = 100.0 * static_cast<double>(bad[t]) / evaluated;
    }
    // No pixel with a result has no average error (NaN: "n/a" in reports, null in
    // JSON), which zero would hide as a perfect score.
    result.avg_error = with_result > 0 ? error_sum / with_result : std::numeric_limits<double>::quiet_NaN();
    result.density_percent = 100.0 * static_cast<double>(with_result) / evaluated;
    return result;
  }
};

std::string describe(const cv::Mat& image) {
  return std::to_string(image.cols) + "x" + std::to_string(image.rows) + " type " +
         std::to_string(image.type());
}

// Optional masks are either absent or CV_8UC1 of the disparity's size.
void check_mask(const cv::Mat& image, const cv::Size& size, const char* what) {
  if (image.empty()) return;
  if (image.type() != CV_8UC1 || image.size() != size) {
    throw std::invalid_argument(std::string("evaluate_disparity: ") + what +
                                " must be CV_8UC1 of the disparity's size, got " +
                                describe(image));
  }
}

void check_inputs(const cv::Mat& disparity, const cv::Mat& ground_truth,
                  const cv::Mat& nonocc_mask, const cv::Mat& selection) {
  if (disparity.empty() || disparity.type() != CV_32FC1) {
    throw std::invalid_argument("evaluate_disparity: disparity must be a non-empty CV_32FC1, got " +
                                describe(disparity));
  }
  if (ground_truth.type() != CV_32FC1 || ground_truth.size() != disparity.size()) {
    throw std::invalid_argument(
        "evaluate_disparity: ground truth must be CV_32FC1 of the disparity's size (" +
        describe(disparity) + "), got " + describe(ground_truth));
  }
  check_mask(nonocc_mask, disparity.size(), "non-occlusion mask");
  check_mask(selection, disparity.size(), "selection");
}

}  // namespace

double ErrorStats::bad(double threshold) const {
  for (std::size_t t = 0; t < kBadThresholds.size(); ++t) {
    if (kBadThresholds[t] == threshold) return bad_percent[t];
  }
  throw std::invalid_argument("ErrorStats::bad: no statistic for threshold " +
                              std::to_string(threshold));
}

SceneScores evaluate_disparity(const cv::Mat& disparity, const cv::Mat& ground_truth,
                               const cv::Mat& nonocc_mask) {
  return evaluate_disparity(disparity, ground_truth, nonocc_mask, cv::Mat());
}

// An empty `selection` selects every pixel; the public overload without it relies on that.
SceneScores evaluate_disparity(const cv::Mat& disparity, const cv::Mat& ground_truth,
                               const cv::Mat& nonocc_mask, const cv::Mat& selection) {
  check_inputs(disparity, ground_truth, nonocc_mask, selection);
  Tally all;
  Tally nonocc;
  for (int y = 0; y < disparity.rows; ++y) {
    const float* d = disparity.ptr<float>(y);
    const float* gt = ground_truth.ptr<float>(y);
    const uchar* mask = nonocc_mask.empty() ? nullptr : nonocc_mask.ptr<uchar>(y);
    const uchar* chosen = selection.empty() ? nullptr : selection.ptr<uchar>(y);
    for (int x = 0; x < disparity.cols; ++x) {
      if (!std::isfinite(gt[x])) continue;  // unknown ground truth: not evaluated
      if (chosen && chosen[x] == 0) continue;
      all.add(d[x], gt[x]);
      if (!mask || mask[x] == 255) nonocc.add(d[x], gt[x]);
    }
  }
  SceneScores scores;
  scores.all = all.stats();
  scores.nonocc = nonocc.stats();
  return scores;
}

ErrorStats average(const std::vector<ErrorStats>& stats) {
  ErrorStats mean;
  if (stats.empty()) return mean;  // nothing to average: all zeros, like an empty region
  double evaluated_sum = 0;
  int with_error = 0;  // scenes that have an average error
  for (const ErrorStats& s : stats) {
    for (std::size_t t = 0; t < kBadThresholds.size(); ++t) mean.bad_percent[t] += s.bad_percent[t];
    if (std::isfinite(s.avg_error)) {
      mean.avg_error += s.avg_error;
      ++with_error;
    }
    mean.density_percent += s.density_percent;
    evaluated_sum += static_cast<double>(s.evaluated);
  }
  const double n = static_cast<double>(stats.size());
  for (double& percent : mean.bad_percent) percent /= n;
  mean.avg_error = with_error > 0 ? mean.avg_error / with_error : std::numeric_limits<double>::quiet_NaN();
  mean.density_percent /= n;
  // Averaged like the other fields (the header's contract), rounded to a whole count.
  mean.evaluated = std::lround(evaluated_sum / n);
  return mean;
}

}  // namespace flexsight

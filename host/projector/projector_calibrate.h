#pragma once
// Calibrating the projector from data: where a pair's stereo match is confident (both
// cameras agree), a left pixel's point is known, so its place in the projector's pattern
// is too. Accumulating the left image's projector light (laser_channel, normalised by its
// local mean and spread, so albedo and gain drop out) at those places over many points
// and depths estimates the pattern image. The projector's pose is checked the same way:
// with a wrong pose, points at different depths land on different pattern pixels, so the
// patterns estimated from two sets of scenes whose surfaces lie at different depths (a
// board at two heights, bins with parts in different places) disagree. One scene alone
// cannot check it: each projector ray meets one surface (docs/projector.md).
#include <opencv2/core.hpp>
#include <vector>

#include "host/projector/projector_view.h"

namespace flexsight {

// A projector at `offset_x_mm` from the middle of the baseline, looking along the
// cameras' axis, rows rectified with theirs, pinhole at the left camera's focal length,
// a square field of `fov_degrees`; its pattern file named `pattern`.
ProjectorCalib projector_on_baseline(const MiddleburyCalib& calib, double fov_degrees, double offset_x_mm,
                                     const std::string& pattern);

// One left view with its confident disparities, ready to be accumulated.
struct CalibrationView {
  cv::Mat normalised;  // laser channel, locally normalised (CV_32FC1)
  cv::Mat disparity;   // CV_32FC1, NaN where not confident
  MiddleburyCalib calib;
};
CalibrationView calibration_view(const cv::Mat& left_rgb8, const cv::Mat& disparity,
                                 const cv::Mat& confident, const MiddleburyCalib& calib);

// The mean normalised light per pattern pixel (CV_32FC1) and how much landed there.
struct PatternEstimate {
  cv::Mat mean, weight;
  // As an 8-bit pattern image: the mean mapped linearly from [-1, 3] to [0, 255].
  cv::Mat image8() const;
};

// Accumulates the views' points whose disparity lies in [min_disparity, max_disparity).
PatternEstimate estimate_pattern(const std::vector<CalibrationView>& views, const ProjectorCalib& projector,
                                 float min_disparity = -1e30f, float max_disparity = 1e30f);

// The share of the pattern a decoder can need that the estimate covers: of the pattern
// pixels the left camera's rows can reach at some disparity (the virtual view,
// projector_view.h), those with weight at least min_weight.
double pattern_coverage(const PatternEstimate& estimate, const MiddleburyCalib& calib,
                        const ProjectorCalib& projector, double min_weight = 0.5);

// ZNCC of two patterns over the pixels where both weights are at least min_weight.
double pattern_agreement(const cv::Mat& a, const cv::Mat& a_weight, const cv::Mat& b, const cv::Mat& b_weight,
                         double min_weight = 0.5);

// The pose check: the agreement between the patterns estimated from the even and the
// odd views (at least two).
double split_agreement(const std::vector<CalibrationView>& views, const ProjectorCalib& projector);

}  // namespace flexsight

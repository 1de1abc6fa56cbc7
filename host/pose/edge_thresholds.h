#pragma once
// What makes the pose stage's edges hold when the image differs from the renders the
// defaults were chosen on: another exposure or gain (the grey levels scaled and shifted),
// lower contrast, more sensor noise. The Canny thresholds are absolute grey-level
// gradients; these helpers bring the image to them (a contrast stretch) and keep them
// above the image's own gradient noise. docs/pose.md ("Edges under noise and gain") has
// the measurements behind them.
#include <opencv2/core.hpp>
#include <string>

#include "host/pose/dcd_tensor.h"

namespace flexsight {

struct CannyThresholds {
  double low = 0.0, high = 0.0;
};

// `grey` (CV_8UC1) stretched in place so that its 2nd and 98th percentiles land on 0 and
// 255 (clipped beyond); left as it is when they lie less than 8 grey levels apart (a flat
// region: stretching would only magnify noise).
void stretch_contrast(cv::Mat& grey);

// The thresholds raised, where needed, above the gradient noise of the region whose
// Sobel derivatives are dx, dy (CV_16S): the noise's standard deviation per derivative
// is taken from their median absolute value (texture-less parts: most pixels see noise
// only; 0.6745 sigma is the median of |N(0, sigma)|), and Canny's L2 magnitude of pure
// noise (Rayleigh) exceeds 4 sigma at 3 pixels in 10,000 and 2 sigma at 14 in 100, so
// high >= 4 sigma keeps edges from starting in noise and low >= 2 sigma keeps them from
// running along it.
CannyThresholds above_gradient_noise(CannyThresholds thresholds, const cv::Mat& dx, const cv::Mat& dy);

// The mode of a command line's `--edges` value: fixed, contrast, noise or contrast+noise;
// InputError naming `option` for anything else.
DcdParams::EdgeThresholds edge_thresholds_named(const std::string& name, const std::string& option);

}  // namespace flexsight

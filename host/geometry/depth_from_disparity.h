#pragma once
// Depth from disparity, once for every caller: Z = StereoCamera::depth(d) (Q, so
// f B / (d + doffs) for a Middlebury rig), scaled to the output unit, per pixel of a
// disparity map. Callers differ only in which pixels have a depth and what the others
// hold, so those are named rules rather than copies of the loop.
#include <opencv2/core.hpp>

#include "host/geometry/stereo_camera.h"

namespace flexsight {

struct DepthRule {
  // Which disparities are converted: all (a non-finite one gives no depth anyway), the
  // matcher's valid ones (finite, >= 0), or the positive ones.
  enum class Disparities { kAll, kNonNegative, kPositive };
  Disparities disparities = Disparities::kAll;
  // Whether a converted depth must also be finite and > 0 to be written.
  bool positive_depth_only = true;
  // What a pixel without a depth holds.
  float no_depth = 0.0f;

  // The point-cloud products (cloud --depth): NaN where the matcher gave no disparity,
  // otherwise whatever Q gives.
  static DepthRule cloud();
  // The pose estimator's depth input: 0 where there is no positive depth. `pick` takes
  // every disparity of its own matcher; `pose --disparity` only positive ones of a file.
  static DepthRule pick() { return {}; }
  static DepthRule pose_input() { return {Disparities::kPositive, true, 0.0f}; }
};

// CV_32FC1 depth of each pixel of a CV_32FC1 `disparity` (left image), in units of
// `metres_per_unit_out` metres (1e-3 for millimetres). `camera` must already be sized to
// the image (StereoCamera::resized_to).
cv::Mat depth_from_disparity(const cv::Mat& disparity, const StereoCamera& camera,
                             double metres_per_unit_out, const DepthRule& rule);

}  // namespace flexsight

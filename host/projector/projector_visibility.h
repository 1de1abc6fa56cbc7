#pragma once
// What the stereo result already says about where a decoded point cannot be. A candidate
// disparity d of left pixel (u, v) is a point on the left camera's ray; it is impossible
//  - when the right camera's consistent match at x = u - d sees a surface farther away
//    (its disparity below d): the point would stand in front of that surface and hide it
//    (free space);
//  - when the projector's ray through the point meets a consistent left surface nearer
//    to the projector (a larger disparity at the same projector column): the point lies
//    in that surface's shadow and no dot can light it.
// Only matches that pass the left/right check count, so the stereo's own errors at the
// asked pixels do not veto anything.
#include <opencv2/core.hpp>

#include "host/projector/projector_view.h"

namespace flexsight {

class StereoVisibility {
 public:
  // raw_left, raw_right: the raw disparities (CV_32FC1); `tolerance` px of slack on both tests.
  StereoVisibility(const cv::Mat& raw_left, const cv::Mat& raw_right, const LeftCamera& camera,
                   const ProjectorCalib& projector, const VirtualView& view, float tolerance);
  bool possible(int u, int v, double d) const;
  bool in_free_space(int u, int v, double d) const;
  bool in_shadow(int u, int v, double d) const;

 private:
  cv::Mat right_consistent_;  // CV_32FC1: the right disparity where consistent, NaN elsewhere
  cv::Mat nearest_;           // CV_32FC1 per view sample: the largest consistent left disparity, -inf none
  double tx_over_b_ = 0, doffs_ = 0;
  const VirtualView* view_ = nullptr;
  float tolerance_ = 2.0f;
};

}  // namespace flexsight

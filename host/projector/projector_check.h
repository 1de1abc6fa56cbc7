#pragma once
// Checking a stereo result against the projector: at each left pixel with a disparity,
// the left window's projector light is compared by ZNCC (projector_decode.h) with the
// pattern as the camera would see it at that disparity, and with the pattern at the
// other disparities within `range` px along the camera-projector row. A match the
// projector disagrees with is flagged: the best score more than 2 px away (outside what
// bad-2 forgives) beats the score at the stereo disparity by `margin`, or the score at
// the stereo disparity is below `floor` while the pattern is lit there. A flagged pixel's
// disparity is invalidated, or, with `replace`, set to the projector's best when that is
// distinct (at least `replace_score`).
#include <opencv2/core.hpp>

#include "host/projector/projector_view.h"

namespace flexsight {

struct ProjectorCheckParams {
  int window = 13;             // odd, camera pixels
  double range = 8.0;          // px of disparity either side of the stereo's searched
  double margin = 0.3;         // best elsewhere minus the score at the stereo disparity
  double floor = -1.0;         // least score at the stereo disparity (-1: no floor)
  double min_texture = 1.0;    // grey levels: the window's spread below which a pixel is not checked
  bool replace = false;        // flagged pixels take the projector's best instead of inf
  double replace_score = 0.5;  // least ZNCC of a replacing best
};

// What the check found at one pixel.
struct PixelCheck {
  bool checked = false;     // window inside the image, enough projector light
  double at_stereo = -1;    // best score within 1 px of the stereo disparity
  double elsewhere = -1;    // best score more than 2 px away, within range
  float best_disparity = 0; // where `elsewhere` was found
};

PixelCheck check_pixel(const cv::Mat& channel, int u, int v, float disparity, const LeftCamera& camera,
                       const ProjectorCalib& projector, const VirtualView& view, const ProjectorCheckParams& params);

struct ProjectorCheckResult {
  cv::Mat flagged;    // CV_8UC1: 255 where the projector disagrees with the stereo disparity
  cv::Mat disparity;  // the input with the flagged pixels inf, or replaced (CV_32FC1)
  int checked = 0, flagged_count = 0, replaced = 0;
};

// Checks every finite, non-negative disparity of `disparity` (CV_32FC1, left view).
ProjectorCheckResult check_with_projector(const cv::Mat& left_rgb8, const cv::Mat& disparity,
                                          const MiddleburyCalib& calib, const ProjectorCalib& projector,
                                          const cv::Mat& pattern, const ProjectorCheckParams& params = {});

}  // namespace flexsight

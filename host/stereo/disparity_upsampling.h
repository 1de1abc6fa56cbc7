#pragma once
// A disparity computed on a pair shrunk by an integer factor, brought back to the full
// size and pixel unit (pick --stereo-downscale: the matcher's time falls with the square
// of the factor).
#include <opencv2/core.hpp>

namespace flexsight {

// `disparity_small`: CV_32FC1; `planes_small`: CV_32FC3 (a, b, c) of the same size, the
// matcher's planes (d = a x + b y + c). Each full-size pixel takes the disparity of the
// small pixel it lies in, moved along that pixel's plane to its own position (a and b,
// disparity per pixel, are the same at every scale), times the scale: slanted surfaces
// stay smooth instead of steps, and no disparity is mixed across a part's edge as
// interpolation would. A pixel whose plane is not finite keeps the plain disparity.
cv::Mat upsample_disparity(const cv::Mat& disparity_small, const cv::Mat& planes_small, cv::Size full);

}  // namespace flexsight

#pragma once
// Pictures for people: colored disparity maps and error maps (8-bit RGB).
#include <opencv2/core.hpp>

namespace flexsight {

// Maps [0, max_disparity] through a perceptual colormap (OpenCV TURBO); pixels without
// a result (non-finite or negative) are black. Returns CV_8UC3 in RGB order.
cv::Mat colorize_disparity(const cv::Mat& disparity, float max_disparity);

// Confidence in [0, 1] through OpenCV's VIRIDIS colormap (dark blue = 0, yellow = 1);
// non-finite values are black. Returns CV_8UC3 in RGB order.
cv::Mat colorize_confidence(const cv::Mat& confidence);

// Per pixel: black where the ground truth is unknown; green shades for |error| <=
// threshold, then yellow to red as the error grows (saturating at 4 * threshold);
// magenta where there is ground truth but no result. Occluded pixels (mask != 255) are
// drawn darker. Returns CV_8UC3 in RGB order.
cv::Mat error_map(const cv::Mat& disparity, const cv::Mat& ground_truth,
                  const cv::Mat& nonocc_mask, float threshold);

}  // namespace flexsight

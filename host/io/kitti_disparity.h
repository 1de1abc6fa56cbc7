#pragma once
// KITTI 2012/2015 disparity maps: 16-bit PNG, disparity = value / 256, 0 = no data.
#include <opencv2/core.hpp>
#include <string>

namespace flexsight {

// Returns CV_32FC1 with +inf where the PNG holds 0. Throws InputError unless the file
// is a single-channel 16-bit PNG.
cv::Mat read_kitti_disparity(const std::string& path);

// Writes CV_32FC1 as a KITTI 16-bit PNG (round(d * 256), clamped to 1..65535 for
// valid values, 0 for non-finite or negative), atomically.
void write_kitti_disparity(const std::string& path, const cv::Mat& disparity);

}  // namespace flexsight

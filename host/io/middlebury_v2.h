#pragma once
// Middlebury v2 ground truth (tsukuba, venus, teddy, cones): 8-bit PNG holding
// disparity * scale, 0 = unknown.
#include <opencv2/core.hpp>
#include <string>

namespace flexsight {

// Returns CV_32FC1, value / scale, +inf where the PNG holds 0. A three-channel PNG
// with equal channels is accepted (some copies are stored that way); anything else
// that is not 8-bit gray throws InputError, as does scale <= 0.
cv::Mat read_middlebury_v2_disparity(const std::string& path, double scale);

// Reads an 8-bit region mask (nonocc.png, all.png, disc.png, mask0nocc.png) as
// CV_8UC1. Throws InputError for a missing file or a mask of another depth.
cv::Mat read_mask(const std::string& path);

}  // namespace flexsight

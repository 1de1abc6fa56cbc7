#pragma once
// Portable Float Map, as Middlebury uses it: header "Pf" (1 channel) or "PF" (3),
// "W H", then a scale whose sign gives the byte order (negative = little-endian),
// then float32 rows stored bottom-up. +inf marks an unknown disparity.
#include <opencv2/core.hpp>
#include <string>

namespace flexsight {

// Returns CV_32FC1 (or CV_32FC3 for "PF") with rows top-down, in host byte order.
// Throws InputError for a missing file, a bad magic, bad or non-positive
// dimensions, a zero scale, or fewer data bytes than the header promises.
cv::Mat read_pfm(const std::string& path);

// Writes CV_32FC1 or CV_32FC3 as little-endian PFM (scale -1), atomically.
void write_pfm(const std::string& path, const cv::Mat& image);

}  // namespace flexsight

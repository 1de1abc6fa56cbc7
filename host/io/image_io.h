#pragma once
// Stereo image input: PNG/PPM/PGM/JPG, 8- or 16-bit, gray or color (alpha dropped).
// Everything is normalised to 8-bit RGB because the matcher's support weights are a
// table indexed by the integer L1 colour difference (see fallback/stereo/weight_table.h).
#include <opencv2/core.hpp>
#include <string>

namespace flexsight {

// Loads `path` as CV_8UC3 in RGB channel order. 16-bit input is scaled by 1/257 with
// rounding; gray is replicated to three channels. Throws InputError for a missing,
// unreadable, empty or undecodable file and for an unsupported depth (e.g. float).
cv::Mat load_rgb8(const std::string& path);

struct StereoPair {
  cv::Mat left;   // CV_8UC3, RGB
  cv::Mat right;  // CV_8UC3, RGB, same size as left
};

// Loads both views; throws InputError naming the right image if sizes differ.
StereoPair load_stereo_pair(const std::string& left_path, const std::string& right_path);

// Writes an 8-bit (or 16-bit) image through cv::imwrite, atomically. `image` in RGB
// order when it has three channels. Throws InputError when encoding fails.
void write_image(const std::string& path, const cv::Mat& image_rgb);

}  // namespace flexsight

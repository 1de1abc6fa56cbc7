#pragma once
// OpenCV's block matchers as the peers of our benchmark report, with the settings the
// issue and the paper compare against (not tuned by us).
#include <opencv2/core.hpp>
#include <string>

namespace flexsight {

enum class OpenCvMatcher { Sgbm, Bm };

// "sgbm" / "bm" -> matcher; false for anything else.
bool parse_opencv_matcher(const std::string& name, OpenCvMatcher& out);
const char* opencv_matcher_name(OpenCvMatcher matcher);
// One line with every setting, for reports.
std::string opencv_matcher_settings(OpenCvMatcher matcher);

// Throws InputError naming `what` (the images) when they are too small for the matcher:
// StereoSGBM needs images wider than numDisparities (ndisp rounded up to 16), StereoBM
// at least 10 x 10 pixels (its 9 x 9 block plus one). OpenCV asserts or fails inside
// otherwise, with messages about its internals.
void check_opencv_matcher_size(OpenCvMatcher matcher, cv::Size size, int ndisp, const std::string& what);

// Disparity of the left view, CV_32FC1; +inf where OpenCV gives no result (left border,
// uniqueness and speckle rejects), so the evaluator counts those pixels as bad.
//   StereoSGBM: MODE_SGBM_3WAY, block 5, P1 8*3*25, P2 32*3*25, uniqueness 10,
//               speckle window 100, speckle range 2, disp12MaxDiff 1, preFilterCap 63.
//   StereoBM:   block 9, preFilterCap 31, textureThreshold 10, uniqueness 15, speckle
//               window 100, speckle range 32, disp12MaxDiff 1 (OpenCV's stereo_match sample).
// numDisparities is ndisp rounded up to a multiple of 16, as both require.
// Checks the size first (check_opencv_matcher_size); an OpenCV failure inside is
// reported as a std::runtime_error that says which matcher failed on which size.
cv::Mat run_opencv_matcher(OpenCvMatcher matcher, const cv::Mat& left_rgb8,
                           const cv::Mat& right_rgb8, int ndisp);

}  // namespace flexsight

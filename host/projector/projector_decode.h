#pragma once
// Decoding the projector as a third view: for left pixels the stereo match leaves without
// a consistent disparity (mostly those the right camera does not see), search the
// disparity along the camera-projector row (projector_view.h): at each candidate compare
// the left window with the pattern as the camera would see it there, assuming the
// surface locally fronto-parallel, by zero-mean normalised cross-correlation (so the
// surface's albedo and the camera's gain do not matter), and keep the best candidate
// when it is distinct: its score at least min_score and above every candidate outside
// its peak by at least min_margin. Otherwise the pixel keeps what it had.
#include <opencv2/core.hpp>
#include <vector>

#include "host/projector/projector_view.h"
#include "host/projector/projector_visibility.h"

namespace flexsight {

struct ProjectorDecodeParams {
  int window = 13;              // odd, camera pixels
  double min_score = 0.5;       // ZNCC of the best candidate
  double min_margin = 0.1;      // best minus the best outside its peak
  int peak_halfwidth = 4;       // candidates (of B / (2 |tx|) px of disparity) that count as the peak
  float lr_tolerance = 1.0f;    // px: the left/right check that picks the pixels to decode
  double min_texture = 1.0;     // grey levels: the left window's spread below which nothing is decoded
  // Slanted windows: besides the fronto-parallel window, surfaces whose disparity changes
  // by s_x per pixel along the row (0.5, 1: the sides the right camera sees at a grazing
  // angle) and s_y per pixel down the column (-1, 1) are tried; the best counts.
  bool slanted = false;
  // Refuse candidates the stereo result rules out (projector_visibility.h).
  bool visibility = false;
  float visibility_tolerance = 2.0f;  // px
};

// The projector's light in an RGB8 image: red minus the mean of green and blue, so that
// grey shading mostly cancels and the red dots remain (CV_32FC1).
cv::Mat laser_channel(const cv::Mat& rgb8);

// Left pixels the stereo match leaves without a consistent disparity (CV_8UC1 255): the
// raw left disparity not finite, or the raw right disparity at x - d disagreeing by more
// than `tolerance`.
cv::Mat left_right_failures(const cv::Mat& raw_left, const cv::Mat& raw_right, float tolerance);

// The left window of `channel` around (u, v), zero mean and unit norm, in `left` (row
// by row); false when it leaves the image or its spread is below min_texture.
bool normalised_window(const cv::Mat& channel, int u, int v, int radius, double min_texture,
                       std::vector<float>& left);

// ZNCC of a normalised_window against the view's samples at column j + offsets (one per
// window pixel) on rows v - radius .. v + radius; -1 where it leaves the view.
double window_score(const std::vector<float>& left, const VirtualView& view, int v, int j, int radius,
                    const std::vector<int>& offsets);

struct PixelDecode {
  float disparity = 0;  // sub-pixel, NaN when none
  double best = -1, second = -1;
  bool distinct(const ProjectorDecodeParams& params) const {
    return best >= params.min_score && best - second >= params.min_margin;
  }
};

// The search at one left pixel of `channel` (laser_channel of the left image); with
// `visibility`, the candidates it rules out are skipped.
PixelDecode decode_pixel(const cv::Mat& channel, int u, int v, const LeftCamera& camera,
                         const ProjectorCalib& projector, const VirtualView& view,
                         const ProjectorDecodeParams& params, const StereoVisibility* visibility = nullptr);

struct ProjectorDecodeResult {
  cv::Mat disparity;  // the input disparity with the decoded pixels replaced (CV_32FC1)
  cv::Mat state;      // CV_8UC1: 0 not asked, 1 decoded, 2 asked but not distinct
  int asked = 0, decoded = 0;
};

// Decodes the pixels of `asked` (CV_8UC1, non-zero) in the left image; params.visibility
// needs the raw disparities (else they may be empty).
ProjectorDecodeResult decode_with_projector(const cv::Mat& left_rgb8, const cv::Mat& disparity,
                                            const cv::Mat& asked, const MiddleburyCalib& calib,
                                            const ProjectorCalib& projector, const cv::Mat& pattern,
                                            const ProjectorDecodeParams& params = {},
                                            const cv::Mat& raw_left = {}, const cv::Mat& raw_right = {});

}  // namespace flexsight

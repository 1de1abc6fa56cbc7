#pragma once
// The matcher on one rectangle of a rectified pair instead of the whole pair: the left
// image cropped to the rectangle (and what the matcher's windows and the disparity range
// need around it), the right image cropped to the columns those disparities reach. Pick
// uses it twice (docs/pick.md, "Stereo where it matters"): the bin's region matched
// coarse, and a candidate's box matched again at full resolution before it is posed.
#include <opencv2/core.hpp>

#include "host/stereo/stereo_backend.h"
#include "host/stereo/stereo_params.h"

namespace flexsight {

// Disparities in full-resolution pixels, both ends included.
struct DisparityRange {
  int min = 0;
  int max = 0;
  int count() const { return max - min + 1; }
};

// Where the matcher runs for a rectangle: `left` is the left image's crop (inside the
// image), the right crop is the same rectangle moved `shift` pixels to the left (it may
// reach past the image's left edge; those columns repeat the edge), and a disparity d of
// the full pair is shift + the crop's disparity, which lies in [0, ndisp - 1].
struct RegionCrop {
  cv::Rect left;
  int shift = 0;
  int ndisp = 2;
  cv::Rect right() const { return left - cv::Point(shift, 0); }
};

// The crop that matches every pixel of `box` (clipped to `image`) within `range`. The
// crop reaches `margin` pixels past the box on every side (the matcher's windows, the
// post-processing's medians) and range.count() more to the left, where the box's
// leftmost pixels find their matches in the shifted right crop. `range.min` is clamped
// at 0 and the crop is widened (inside the image) to at least ndisp pixels, which the
// matcher needs.
RegionCrop plan_region_crop(const cv::Rect& box, DisparityRange range, int margin, cv::Size image);

// The pixels a crop needs around its box for `params`: half the largest window of the
// matcher and of its median filters, plus a few pixels.
int region_margin(const StereoParams& params);

// The disparity (CV_32FC1, full-resolution pixels) of every pixel of `crop.left`, the
// pair matched in the crop with `params` (ndisp replaced by the crop's). `downscale` > 1:
// both crops shrunk by it (area averaging), the disparity brought back along the
// matcher's planes (host/stereo/disparity_upsampling.h). Deterministic: the same inputs
// give the same bytes.
cv::Mat match_region(StereoBackend& stereo, const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                     const RegionCrop& crop, StereoParams params, int downscale = 1);

// The disparity range of `disparity` (CV_32FC1, full size) inside `box`: its finite
// values' minimum and maximum widened by `margin` pixels, the minimum at least 0. An
// empty range (max < min) when the box holds no finite value.
DisparityRange disparity_range_in(const cv::Mat& disparity, const cv::Rect& box, int margin);

struct BoxRefinement {
  // Pixels the range read from the coarse disparity is widened by on each side: a coarse
  // level's disparity is a few full-size pixels off at a part's edge.
  int range_margin = 8;
  // The matcher's coarsest level is at most this wide (StereoParams::coarsest_width; 0:
  // the params'). A box's crop is one or two of the whole pair's levels wide, so with the
  // pair's 128 px its coarsest level, which starts from random planes with the dense
  // window step, takes half the crop's time; 32 px puts it at 1/16 of the crop
  // (docs/tuning-log.md).
  int coarsest_width = 32;
  // The range reaches at least this many pixels above its minimum (refine_pick_box sets
  // it from the box's size): a coarse level loses the tops of small, tall parts.
  int min_span = 0;
};

// A candidate's box matched again at full resolution: the range is read from the coarse
// `disparity` inside the box, the box matched in its crop (plan_region_crop) with
// `params`, and the result written over `disparity` (CV_32FC1, the pair's size) inside
// the box (clipped to the image). Returns the crop that was matched (an empty `left`
// when the box was empty or held no finite disparity: nothing changes).
RegionCrop refine_disparity_in_box(StereoBackend& stereo, const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                                   const StereoParams& params, const cv::Rect& box, cv::Mat& disparity,
                                   const BoxRefinement& refinement = BoxRefinement());

}  // namespace flexsight

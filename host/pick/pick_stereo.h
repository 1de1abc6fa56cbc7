#pragma once
// Pick's stereo step: which pixels are matched at which size (docs/pick.md, "Stereo where
// it matters").
#include <opencv2/core.hpp>
#include <string>

#include "host/geometry/stereo_camera.h"
#include "host/pick/bin_region.h"
#include "host/stereo/stereo_backend.h"

namespace flexsight {

enum class StereoPlan {
  // The whole pair at 1/downscale of its size, over the pair's ndisp.
  kFull,
  // The whole pair at 1/BinRegionPlan::search_downscale (to find the bin, find_bin_region), then the
  // bin's rectangle alone at 1/downscale over the bin's disparity range; outside the bin
  // the coarse match stays.
  kBinRegion,
};

// How kBinRegion matches (docs/tuning-log.md has the measurements behind each default).
struct BinRegionPlan {
  // The whole pair is matched at 1/search_downscale to find the bin: 1/8 of 1280 x 960
  // still shows the floor and the walls (1/16 lost parts of the range on dev bins).
  int search_downscale = 8;
  // ... but the searched pair stays at least this wide: a 640 x 480 pair at 1/8 (80 px)
  // no longer shows the walls, and its region came out as the whole image.
  int min_search_width = 160;
  // The matcher's coarsest level is at most this wide in both matches
  // (StereoParams::coarsest_width). Both images are a few hundred pixels wide or less, so
  // with the pair's 128 px the coarsest level, which starts from random planes with the
  // dense window step, would take about half the time.
  int coarsest_width = 32;
  BinRegionOptions region;
};

// The downscale the whole pair is searched at for the bin: plan.search_downscale, less
// where the pair would come out narrower than plan.min_search_width.
int bin_search_downscale(int pair_width, const BinRegionPlan& plan);

// "full" or "roi"; false for another name.
bool parse_stereo_plan(const std::string& name, StereoPlan& plan);
const char* stereo_plan_name(StereoPlan plan);

// The matcher on the pair shrunk by `downscale` (area averaging), its disparity brought
// back to the pair's size along the matcher's planes (host/stereo/disparity_upsampling.h).
cv::Mat disparity_at_scale(StereoBackend& stereo, const cv::Mat& left, const cv::Mat& right, StereoParams params,
                           int downscale, const ProgressCallback& progress, std::string* path);

struct PickDisparity {
  cv::Mat disparity;  // CV_32FC1, the pair's size
  BinRegion region;   // kBinRegion: the bin's rectangle and range (found or not)
};

// The disparity pick works on, by `plan` (see StereoPlan). `rig`: the pair's calibration at
// its size. `path` (when given) receives the matcher's path of the last run.
PickDisparity pick_disparity(StereoBackend& stereo, const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                             const StereoCamera& rig, const StereoParams& params, StereoPlan plan, int downscale,
                             const ProgressCallback& progress = {}, std::string* path = nullptr,
                             const BinRegionPlan& bin_plan = BinRegionPlan());

// A candidate's box matched again at full resolution before it is posed
// (refine_disparity_in_box, with `params` as for the whole pair) and pick's depth
// rewritten inside it from the refined disparity. `rig`: the pair's calibration at its
// size; `disparity`, `depth_mm`: CV_32FC1 of the pair's size, changed inside the box
// (clipped to the image) only. The box's range reaches at least as high as a surface
// `part_diameter_mm` (the candidate's part's diameter; 0: unknown) or the box's diagonal,
// whichever is more, above the box's lowest surface: the coarse match misses the tops of
// small parts standing up, which look small from above. Returns the crop matched (empty:
// nothing changed).
RegionCrop refine_pick_box(StereoBackend& stereo, const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                           const StereoCamera& rig, const StereoParams& params, const cv::Rect& box,
                           double part_diameter_mm, cv::Mat& disparity, cv::Mat& depth_mm,
                           const BoxRefinement& refinement = BoxRefinement());

}  // namespace flexsight

#include "host/pick/pick_stereo.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "host/geometry/depth_from_disparity.h"
#include "host/geometry/stereo_rig.h"
#include "host/pick/stereo_region.h"
#include "host/stereo/disparity_upsampling.h"

namespace flexsight {
namespace {

// The disparity of depth `z` (the rig's unit): StereoCamera::depth inverted.
double rig_disparity_at_depth(const StereoCamera& rig, double z) {
  const Eigen::Matrix4d& Q = rig.Q;
  return (Q(2, 3) - z * Q(3, 3)) / (z * Q(3, 2) - Q(2, 2));
}

}  // namespace

bool parse_stereo_plan(const std::string& name, StereoPlan& plan) {
  if (name == "full") {
    plan = StereoPlan::kFull;
  } else if (name == "roi") {
    plan = StereoPlan::kBinRegion;
  } else {
    return false;
  }
  return true;
}

const char* stereo_plan_name(StereoPlan plan) { return plan == StereoPlan::kFull ? "full" : "roi"; }

cv::Mat disparity_at_scale(StereoBackend& stereo, const cv::Mat& left, const cv::Mat& right, StereoParams params,
                           int downscale, const ProgressCallback& progress, std::string* path) {
  if (downscale <= 1) return stereo.run(left, right, params, progress, path).disparity;
  const cv::Size small(std::max(1, left.cols / downscale), std::max(1, left.rows / downscale));
  cv::Mat left_small, right_small;
  cv::resize(left, left_small, small, 0, 0, cv::INTER_AREA);
  cv::resize(right, right_small, small, 0, 0, cv::INTER_AREA);
  const double to_full = static_cast<double>(left.cols) / small.width;
  params.ndisp = std::max(2, static_cast<int>(std::ceil(params.ndisp / to_full)));
  const StereoResult result = stereo.run(left_small, right_small, params, progress, path);
  return upsample_disparity(result.disparity, result.planes_left, left.size());
}

int bin_search_downscale(int pair_width, const BinRegionPlan& plan) {
  return std::clamp(pair_width / std::max(1, plan.min_search_width), 1, std::max(1, plan.search_downscale));
}

PickDisparity pick_disparity(StereoBackend& stereo, const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                             const StereoCamera& rig, const StereoParams& params, StereoPlan plan, int downscale,
                             const ProgressCallback& progress, std::string* path, const BinRegionPlan& bin_plan) {
  PickDisparity out;
  if (plan == StereoPlan::kFull) {
    out.disparity = disparity_at_scale(stereo, left_rgb8, right_rgb8, params, downscale, progress, path);
    return out;
  }
  // The bin found in a coarse match of the whole pair; that match stays outside it.
  StereoParams region_params = params;
  region_params.coarsest_width = bin_plan.coarsest_width;
  out.disparity = disparity_at_scale(stereo, left_rgb8, right_rgb8, region_params,
                                     bin_search_downscale(left_rgb8.cols, bin_plan), progress, path);
  out.region = find_bin_region(out.disparity, rig.resized_to(left_rgb8.cols, left_rgb8.rows), params.ndisp,
                               bin_plan.region);
  if (progress) progress("the bin's region");
  const RegionCrop crop = plan_region_crop(out.region.rect, out.region.range, region_margin(params) * downscale,
                                           left_rgb8.size());
  const cv::Mat matched = match_region(stereo, left_rgb8, right_rgb8, crop, region_params, downscale);
  matched(out.region.rect - crop.left.tl()).copyTo(out.disparity(out.region.rect));
  return out;
}

RegionCrop refine_pick_box(StereoBackend& stereo, const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                           const StereoCamera& rig, const StereoParams& params, const cv::Rect& box,
                           double part_diameter_mm, cv::Mat& disparity, cv::Mat& depth_mm,
                           const BoxRefinement& refinement) {
  const cv::Rect inside = box & cv::Rect(cv::Point(), disparity.size());
  BoxRefinement spanned = refinement;
  const DisparityRange coarse = disparity_range_in(disparity, inside, 0);
  Eigen::Vector3d p;
  if (coarse.max >= coarse.min && rig.point(inside.x, inside.y, coarse.min, p)) {
    // The lowest surface's depth, less the part's diameter or the box's diagonal there.
    const double focal = stereo_rig_from(rig, disparity.cols, disparity.rows).left.fx;
    const double depth = p.z();
    const double rise = std::max(std::hypot(inside.width, inside.height) * depth / focal,
                                 part_diameter_mm * 1e-3 / rig.metres_per_unit);
    const double top = rig_disparity_at_depth(rig, depth - rise);
    if (std::isfinite(top)) spanned.min_span = std::max(spanned.min_span, static_cast<int>(std::ceil(top)) - coarse.min);
  }
  const RegionCrop crop = refine_disparity_in_box(stereo, left_rgb8, right_rgb8, params, box, disparity, spanned);
  if (crop.left.empty()) return crop;
  // Depth depends on the disparity alone, so the box's part of the map converts on its own.
  depth_from_disparity(disparity(inside), rig, 1e-3, DepthRule::pick()).copyTo(depth_mm(inside));
  return crop;
}

}  // namespace flexsight

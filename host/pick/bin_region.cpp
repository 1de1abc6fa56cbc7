#include "host/pick/bin_region.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "host/geometry/depth_from_disparity.h"
#include "host/geometry/stereo_rig.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

// 255 where a pixel has a depth no deeper than the floor's level less the tolerance.
cv::Mat at_or_above_floor(const cv::Mat& disparity, const StereoCamera& rig, const FloorPlane& floor,
                          double below_floor_mm) {
  cv::Mat mask(disparity.size(), CV_8UC1, cv::Scalar(0));
  Eigen::Vector3d p;
  for (int y = 0; y < disparity.rows; ++y) {
    const float* d = disparity.ptr<float>(y);
    unsigned char* out = mask.ptr<unsigned char>(y);
    for (int x = 0; x < disparity.cols; ++x) {
      if (!std::isfinite(d[x]) || !rig.point(x, y, d[x], p) || !(p.z() > 0.0)) continue;
      if (floor.height(p * (rig.metres_per_unit * 1e3)) >= -below_floor_mm) out[x] = 255;
    }
  }
  return mask;
}

// The largest 8-connected set of `mask`; an empty rectangle when the mask is empty.
cv::Rect largest_component(const cv::Mat& mask, cv::Mat& component) {
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int best = 0;
  for (int i = 1; i < count; ++i) {
    if (best == 0 || stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = i;
  }
  if (best == 0) return {};
  component = labels == best;
  return {stats.at<int>(best, cv::CC_STAT_LEFT), stats.at<int>(best, cv::CC_STAT_TOP),
          stats.at<int>(best, cv::CC_STAT_WIDTH), stats.at<int>(best, cv::CC_STAT_HEIGHT)};
}

}  // namespace

void BinRegionOptions::check() const {
  if (!(below_floor_mm >= 0.0)) throw InputError("bin region", "the depth below the floor must not be negative");
  if (opening_px < 1) throw InputError("bin region", "the opening needs at least one pixel");
  if (rect_margin_px < 0 || disparity_margin < 0) throw InputError("bin region", "margins must not be negative");
  floor.check();
}

BinRegion find_bin_region(const cv::Mat& disparity, const StereoCamera& rig, int ndisp,
                          const BinRegionOptions& options) {
  options.check();
  CV_Assert(disparity.type() == CV_32FC1);
  BinRegion region;
  const cv::Rect image(cv::Point(), disparity.size());
  region.rect = image;
  region.range = {0, std::max(1, ndisp - 1)};
  const cv::Mat depth_mm = depth_from_disparity(disparity, rig, 1e-3, DepthRule::pick());
  region.floor = fit_floor_plane(depth_mm, stereo_rig_from(rig, disparity.cols, disparity.rows).left, options.floor);
  if (!region.floor.found) return region;

  cv::Mat mask = at_or_above_floor(disparity, rig, region.floor, options.below_floor_mm);
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN,
                   cv::getStructuringElement(cv::MORPH_RECT, cv::Size(options.opening_px, options.opening_px)));
  cv::Mat component;
  const cv::Rect bin = largest_component(mask, component);
  if (bin.empty()) return region;

  double low = 0.0, high = 0.0;
  cv::minMaxLoc(disparity, &low, &high, nullptr, nullptr, component);
  const int m = options.rect_margin_px;
  region.rect = cv::Rect(bin.x - m, bin.y - m, bin.width + 2 * m, bin.height + 2 * m) & image;
  region.range.min = std::max(0, static_cast<int>(std::floor(low)) - options.disparity_margin);
  region.range.max = std::min(ndisp - 1, static_cast<int>(std::ceil(high)) + options.disparity_margin);
  region.range.max = std::max(region.range.max, region.range.min + 1);
  region.found = true;
  return region;
}

}  // namespace flexsight

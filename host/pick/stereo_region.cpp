#include "host/pick/stereo_region.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "host/stereo/disparity_upsampling.h"

namespace flexsight {
namespace {

// `rect` of `image`, the columns left of the image repeating its first column (a right
// crop shifted past the image's left edge). Rows and the right side are inside by
// construction (plan_region_crop).
cv::Mat crop_with_edge(const cv::Mat& image, const cv::Rect& rect) {
  const cv::Rect inside = rect & cv::Rect(cv::Point(), image.size());
  cv::Mat crop;
  if (inside.width <= 0 || inside.height != rect.height) return crop;
  cv::copyMakeBorder(image(inside), crop, 0, 0, inside.x - rect.x, rect.br().x - inside.br().x, cv::BORDER_REPLICATE);
  return crop;
}

}  // namespace

int region_margin(const StereoParams& params) {
  const int widest = std::max({params.window, params.median_window, params.final_median_window});
  return widest / 2 + 4;
}

RegionCrop plan_region_crop(const cv::Rect& box, DisparityRange range, int margin, cv::Size image) {
  RegionCrop crop;
  const cv::Rect inside = box & cv::Rect(cv::Point(), image);
  if (inside.empty()) return crop;
  range.min = std::max(0, range.min);
  range.max = std::max(range.max, range.min + 1);
  crop.shift = range.min;
  crop.ndisp = std::min(range.count(), image.width);
  int x0 = std::max(0, inside.x - crop.ndisp - margin);
  int x1 = std::min(image.width, inside.br().x + margin);
  if (x1 - x0 < crop.ndisp) {  // a box at the image's left edge: the crop grows to the right
    x1 = std::min(image.width, x0 + crop.ndisp);
    x0 = std::max(0, x1 - crop.ndisp);
  }
  const int y0 = std::max(0, inside.y - margin);
  const int y1 = std::min(image.height, inside.br().y + margin);
  crop.left = cv::Rect(x0, y0, x1 - x0, y1 - y0);
  return crop;
}

cv::Mat match_region(StereoBackend& stereo, const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                     const RegionCrop& crop, StereoParams params, int downscale) {
  const cv::Mat left = left_rgb8(crop.left).clone();
  const cv::Mat right = crop_with_edge(right_rgb8, crop.right());
  cv::Mat disparity;
  if (downscale <= 1) {
    params.ndisp = crop.ndisp;
    disparity = stereo.run(left, right, params).disparity;
  } else {
    const cv::Size small(std::max(1, left.cols / downscale), std::max(1, left.rows / downscale));
    cv::Mat left_small, right_small;
    cv::resize(left, left_small, small, 0, 0, cv::INTER_AREA);
    cv::resize(right, right_small, small, 0, 0, cv::INTER_AREA);
    const double to_full = static_cast<double>(left.cols) / small.width;
    params.ndisp = std::min(small.width, std::max(2, static_cast<int>(std::ceil(crop.ndisp / to_full))));
    const StereoResult result = stereo.run(left_small, right_small, params);
    disparity = upsample_disparity(result.disparity, result.planes_left, left.size());
  }
  disparity += static_cast<float>(crop.shift);  // NaN stays NaN
  return disparity;
}

DisparityRange disparity_range_in(const cv::Mat& disparity, const cv::Rect& box, int margin) {
  const cv::Rect inside = box & cv::Rect(cv::Point(), disparity.size());
  float low = INFINITY, high = -INFINITY;
  for (int y = inside.y; y < inside.br().y; ++y) {
    const float* row = disparity.ptr<float>(y);
    for (int x = inside.x; x < inside.br().x; ++x) {
      if (!std::isfinite(row[x])) continue;
      low = std::min(low, row[x]);
      high = std::max(high, row[x]);
    }
  }
  if (!(low <= high)) return {0, -1};
  return {std::max(0, static_cast<int>(std::floor(low)) - margin), static_cast<int>(std::ceil(high)) + margin};
}

RegionCrop refine_disparity_in_box(StereoBackend& stereo, const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                                   const StereoParams& params, const cv::Rect& box, cv::Mat& disparity,
                                   const BoxRefinement& refinement) {
  const cv::Rect inside = box & cv::Rect(cv::Point(), disparity.size());
  DisparityRange range = disparity_range_in(disparity, inside, refinement.range_margin);
  if (inside.empty() || range.max < range.min) return {};
  range.max = std::max(range.max, range.min + refinement.min_span);
  StereoParams crop_params = params;
  if (refinement.coarsest_width > 0) crop_params.coarsest_width = refinement.coarsest_width;
  const RegionCrop crop = plan_region_crop(inside, range, region_margin(params), disparity.size());
  const cv::Mat matched = match_region(stereo, left_rgb8, right_rgb8, crop, crop_params);
  matched(inside - crop.left.tl()).copyTo(disparity(inside));
  return crop;
}

}  // namespace flexsight

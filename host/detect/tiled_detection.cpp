#include "host/detect/tiled_detection.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

// A box edge this near to a tile's inner edge counts as cut by it.
constexpr float kCutMarginPx = 2.0f;

float iou(const ObjectDetection& a, const ObjectDetection& b) {
  const float w = std::min(a.box[2], b.box[2]) - std::max(a.box[0], b.box[0]);
  const float h = std::min(a.box[3], b.box[3]) - std::max(a.box[1], b.box[1]);
  if (w <= 0.0f || h <= 0.0f) return 0.0f;
  const float inter = w * h;
  const float area_a = (a.box[2] - a.box[0]) * (a.box[3] - a.box[1]);
  const float area_b = (b.box[2] - b.box[0]) * (b.box[3] - b.box[1]);
  return inter / (area_a + area_b - inter);
}

// Starts of tiles of `tile` along `length`, spread evenly so that neighbours are at
// most `stride` apart, the first at 0 and the last ending at the edge.
std::vector<int> tile_starts(int length, int tile, int stride) {
  if (tile >= length) return {0};
  const int span = length - tile;
  const int gaps = (span + stride - 1) / stride;
  std::vector<int> starts;
  for (int i = 0; i <= gaps; ++i) starts.push_back(static_cast<int>(std::lround(static_cast<double>(i) * span / gaps)));
  return starts;
}

// Whether `d` touches an edge of `tile` that lies inside `bounds` (the image or the
// plan's region): there a neighbouring tile sees the part whole.
bool cut_by_tile_edge(const ObjectDetection& d, const cv::Rect& tile, const cv::Rect& bounds) {
  return (tile.x > bounds.x && d.box[0] <= tile.x + kCutMarginPx) ||
         (tile.y > bounds.y && d.box[1] <= tile.y + kCutMarginPx) ||
         (tile.br().x < bounds.br().x && d.box[2] >= tile.br().x - kCutMarginPx) ||
         (tile.br().y < bounds.br().y && d.box[3] >= tile.br().y - kCutMarginPx);
}

// The part of `image` the plan covers: its region clipped to the image, else the image.
cv::Rect plan_bounds(cv::Size image, const TilingPlan& plan) {
  const cv::Rect whole(cv::Point(), image);
  if (plan.region.empty()) return whole;
  const cv::Rect clipped = plan.region & whole;
  return clipped.empty() ? whole : clipped;
}

}  // namespace

TilingPlan tiling_for_part_sizes(cv::Size image, double typical_part, double largest_part, int min_tile) {
  TilingPlan plan;
  if (!(typical_part > 0.0) || !(largest_part > 0.0)) return plan;
  const int tile = std::max(min_tile, static_cast<int>(std::lround(typical_part / kTrainingPartFraction)));
  if (tile * 4 >= std::min(image.width, image.height) * 3) return plan;
  plan.tile = tile;
  plan.stride = std::max(tile / 4, static_cast<int>(std::floor(tile - 1.1 * largest_part)));
  return plan;
}

TilingPlan fixed_tiling(int tile) {
  if (tile <= 0) return {};
  return {tile, std::max(1, tile * 3 / 4)};
}

bool tile_fits(cv::Size image, int tile) { return tile <= image.width && tile <= image.height; }

std::vector<cv::Rect> detection_tiles(cv::Size image, const TilingPlan& plan) {
  std::vector<cv::Rect> tiles;
  if (plan.tile <= 0) return tiles;
  const cv::Rect bounds = plan_bounds(image, plan);
  const int stride = std::clamp(plan.stride, 1, plan.tile);
  for (int y : tile_starts(bounds.height, plan.tile, stride)) {
    for (int x : tile_starts(bounds.width, plan.tile, stride)) {
      tiles.emplace_back(cv::Rect(bounds.x + x, bounds.y + y, plan.tile, plan.tile) & bounds);
    }
  }
  return tiles;
}

std::vector<ObjectDetection> detect_in_tiles(
    const std::function<std::vector<ObjectDetection>(const cv::Mat&)>& detect, const cv::Mat& image,
    const TilingPlan& plan, float iou_threshold) {
  std::vector<cv::Rect> tiles = detection_tiles(image.size(), plan);
  if (tiles.empty() && plan.region.empty()) return detect(image);
  const cv::Rect bounds = plan_bounds(image.size(), plan);
  if (tiles.empty()) tiles.push_back(bounds);
  std::vector<ObjectDetection> all;
  for (const cv::Rect& tile : tiles) {
    for (ObjectDetection d : detect(image(tile))) {
      d.box[0] += tile.x;
      d.box[2] += tile.x;
      d.box[1] += tile.y;
      d.box[3] += tile.y;
      if (!cut_by_tile_edge(d, tile, bounds)) all.push_back(d);
    }
  }
  // Best first; ties in the order the tiles found them, so the result does not depend on
  // the sort's implementation.
  std::stable_sort(all.begin(), all.end(),
                   [](const ObjectDetection& a, const ObjectDetection& b) { return a.score > b.score; });
  std::vector<ObjectDetection> kept;
  for (const ObjectDetection& d : all) {
    const bool suppressed = std::any_of(kept.begin(), kept.end(), [&](const ObjectDetection& k) {
      return k.category_id == d.category_id && iou(k, d) > iou_threshold;
    });
    if (!suppressed) kept.push_back(d);
  }
  return kept;
}

void check_tile_fits(int tile, cv::Size image, const std::string& image_name) {
  if (tile_fits(image, tile)) return;
  throw InputError("option --tile", std::to_string(tile) + " pixels is larger than " + image_name + " (" +
                                        std::to_string(image.width) + "x" + std::to_string(image.height) +
                                        "); give at most " + std::to_string(std::min(image.width, image.height)) +
                                        " or 0 for the whole image");
}

}  // namespace flexsight

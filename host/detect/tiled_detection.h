#pragma once
// Detection in overlapping tiles, for parts that are small in a large image. The
// detector sees a 300x300 resize of what it is given; its training images show parts
// from 0.1 to 0.83 of the image's width (docs/synth.md), so a 100-pixel part in a
// 1280x960 bin image is 23 pixels wide for the network, below anything it learnt. Cut
// into tiles a few part-diameters wide, the same part is seen at a size it knows
// (slicing-aided inference, as SAHI does).
//
//   TilingPlan plan = tiling_for_part_sizes(image.size(), typical_part_px, largest_part_px);
//   auto found = detect_in_tiles([&](const cv::Mat& tile) { return detector.detect(tile); },
//                                image, plan, 0.6f);
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/detect/ssd_detector.h"

namespace flexsight {

// The share of a training image's width a part spans, at the geometric middle of the
// training sizes (sqrt(0.1 x 0.83)): the size tiles are chosen to give a part.
constexpr double kTrainingPartFraction = 0.29;

struct TilingPlan {
  // Square tiles of this many pixels (clipped at the image's edges); 0: the whole image
  // only.
  int tile = 0;
  // Pixels between the starts of neighbouring tiles (at most `tile`).
  int stride = 0;
  // Where parts can be (e.g. a bin's inside, host/stereo's region of interest): tiles
  // cover it alone and its edges count as the image's. Empty: the whole image.
  cv::Rect region;
};

// Tiles for parts about `typical_part` pixels across: tile = typical_part /
// kTrainingPartFraction, at least `min_tile`; neighbours overlap by 1.1 times the
// largest part, so that every part lies whole in some tile (the stride at least a
// quarter tile). The whole image only (tile 0) when a tile would reach 3/4 of the
// image's shorter side: tiles would add nothing.
TilingPlan tiling_for_part_sizes(cv::Size image, double typical_part, double largest_part, int min_tile = 300);

// Square tiles of `tile` pixels, neighbours overlapping by a quarter tile (stride 3/4
// tile): the plan for a tile size given by hand (pick's, detect's and eval-det's --tile N).
// The whole image only for tile 0.
TilingPlan fixed_tiling(int tile);

// Whether tiles of `tile` pixels fit in `image` (neither side shorter than a tile): a
// larger tile would only be the image clipped, which the whole-image detection is.
bool tile_fits(cv::Size image, int tile);

// Throws InputError naming --tile when tiles of `tile` pixels do not fit in `image`, the
// picture read from `image_name` (tile 0 always fits).
void check_tile_fits(int tile, cv::Size image, const std::string& image_name);

// The tiles of `plan` over `image` (over plan.region within it, when given), row by row,
// spread evenly with neighbours at most plan.stride apart; the last row and column end
// at the image's (region's) edge. Empty when plan.tile is 0.
std::vector<cv::Rect> detection_tiles(cv::Size image, const TilingPlan& plan);

// `detect` on every tile (on the whole image, or plan.region, when plan.tile is 0; the whole image is
// not added to tiles: there the parts are below the training sizes, and its boxes are
// the ones spanning several parts); a tile's boxes moved into the image's pixels, those
// touching one of the tile's edges inside the image dropped (a cut part: a neighbouring
// tile sees it whole), then per-class suppression across tiles (a box goes when its IoU
// with a better one of its class exceeds `iou`). Best first.
std::vector<ObjectDetection> detect_in_tiles(
    const std::function<std::vector<ObjectDetection>(const cv::Mat&)>& detect, const cv::Mat& image,
    const TilingPlan& plan, float iou);

}  // namespace flexsight

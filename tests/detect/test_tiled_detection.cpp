// Detection in tiles (host/detect/tiled_detection.h): the tiles' geometry, and the
// merging of what a detector finds in them, with a detector that reports the white
// rectangles of a picture as they appear in each tile (clipped at its edges, as a real
// one reports a cut part).
#include "host/detect/tiled_detection.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace flexsight {
namespace {

// Every white rectangle of `tile` as a box of category 1 with score 0.9: what an ideal
// detector returns, a part cut by the tile's edge included (its box ends at the edge).
std::vector<ObjectDetection> white_rectangles(const cv::Mat& tile) {
  cv::Mat grey;
  cv::cvtColor(tile, grey, cv::COLOR_BGR2GRAY);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(grey > 128, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  std::vector<ObjectDetection> found;
  for (const auto& contour : contours) {
    const cv::Rect r = cv::boundingRect(contour);
    ObjectDetection d;
    d.category_id = 1;
    d.score = 0.9f;
    d.box[0] = static_cast<float>(r.x);
    d.box[1] = static_cast<float>(r.y);
    d.box[2] = static_cast<float>(r.x + r.width);
    d.box[3] = static_cast<float>(r.y + r.height);
    found.push_back(d);
  }
  return found;
}

TEST(TiledDetection, TilesCoverTheImageAndEndAtItsEdges) {
  const cv::Size image(1280, 960);
  const TilingPlan plan{400, 250, {}};
  const std::vector<cv::Rect> tiles = detection_tiles(image, plan);
  // Columns at 0, 220, 440, 660, 880 (the last ending at 1280), rows at 0, 187, 373, 560:
  // spread evenly, never more than the stride apart.
  ASSERT_EQ(tiles.size(), 5u * 4u);
  EXPECT_EQ(tiles[1].x, 220);
  EXPECT_EQ(tiles[5].y, 187);
  cv::Mat covered(image, CV_8UC1, cv::Scalar(0));
  for (const cv::Rect& tile : tiles) {
    EXPECT_EQ(tile.size(), cv::Size(400, 400));
    covered(tile).setTo(255);
  }
  EXPECT_EQ(cv::countNonZero(covered), image.area());
  EXPECT_EQ(tiles.back(), cv::Rect(880, 560, 400, 400));
}

TEST(TiledDetection, PlanGivesPartsTheTrainingSizeAndOverlapsByTheLargestPart) {
  // 100-pixel parts: 345-pixel tiles (100 / 0.29), neighbours overlapping by 1.1 x 150.
  const TilingPlan plan = tiling_for_part_sizes({1280, 960}, 100.0, 150.0);
  EXPECT_EQ(plan.tile, 345);
  EXPECT_EQ(plan.stride, 345 - 165);
  // Every part up to the largest lies whole in some tile: the overlap holds it.
  EXPECT_GE(plan.tile - plan.stride, 1.1 * 150.0 - 1.0);
  // Parts large in the image: one tile would be most of it, so the whole image only.
  EXPECT_EQ(tiling_for_part_sizes({1280, 960}, 250.0, 300.0).tile, 0);
  // Small parts: never below the network's input size.
  EXPECT_EQ(tiling_for_part_sizes({1280, 960}, 40.0, 60.0).tile, 300);
  // No depth, no size: the whole image.
  EXPECT_EQ(tiling_for_part_sizes({1280, 960}, 0.0, 0.0).tile, 0);
}

TEST(TiledDetection, EveryPartFoundOnceWholeEvenWhereTilesCutIt) {
  cv::Mat image(600, 800, CV_8UC3, cv::Scalar(40, 40, 40));
  // Parts across the tiles' edges (tiles of 300 at stride 200: edges at 200, 300, 400, ...).
  const std::vector<cv::Rect> parts = {{180, 150, 60, 50}, {280, 270, 70, 60}, {500, 100, 40, 90},
                                       {690, 480, 80, 80}, {20, 20, 50, 40}};
  for (const cv::Rect& r : parts) cv::rectangle(image, r, cv::Scalar(255, 255, 255), cv::FILLED);
  const std::vector<ObjectDetection> found = detect_in_tiles(white_rectangles, image, TilingPlan{300, 200, {}}, 0.5f);
  ASSERT_EQ(found.size(), parts.size());
  for (const cv::Rect& r : parts) {
    const bool whole = std::any_of(found.begin(), found.end(), [&](const ObjectDetection& d) {
      return d.box[0] == r.x && d.box[1] == r.y && d.box[2] == r.x + r.width && d.box[3] == r.y + r.height;
    });
    EXPECT_TRUE(whole) << "part at " << r.x << ", " << r.y << " not found whole";
  }
}

TEST(TiledDetection, ARegionIsTiledAloneAndItsEdgesCutNothing) {
  cv::Mat image(600, 800, CV_8UC3, cv::Scalar(40, 40, 40));
  // Inside the region (100..700 x 50..550), one part on its left edge and one across a
  // tile seam; one outside it, which is not looked at.
  const cv::Rect region(100, 50, 600, 500);
  const std::vector<cv::Rect> inside = {{100, 200, 60, 50}, {380, 260, 70, 60}};
  const cv::Rect outside(20, 20, 50, 40);
  for (const cv::Rect& r : inside) cv::rectangle(image, r, cv::Scalar(255, 255, 255), cv::FILLED);
  cv::rectangle(image, outside, cv::Scalar(255, 255, 255), cv::FILLED);
  TilingPlan plan{300, 200, region};
  const std::vector<cv::Rect> tiles = detection_tiles(image.size(), plan);
  ASSERT_EQ(tiles.size(), 6u);  // columns at 100, 250, 400; rows at 50, 250
  for (const cv::Rect& tile : tiles) EXPECT_EQ(tile & region, tile);
  const auto expect_inside_found_whole = [&](const std::vector<ObjectDetection>& found) {
    ASSERT_EQ(found.size(), inside.size());
    for (const cv::Rect& r : inside) {
      const bool whole = std::any_of(found.begin(), found.end(), [&](const ObjectDetection& d) {
        return d.box[0] == r.x && d.box[1] == r.y && d.box[2] == r.x + r.width && d.box[3] == r.y + r.height;
      });
      EXPECT_TRUE(whole) << "part at " << r.x << ", " << r.y << " not found whole";
    }
  };
  expect_inside_found_whole(detect_in_tiles(white_rectangles, image, plan, 0.5f));
  // Without tiles the region is detected as one image, its boxes in the image's pixels.
  plan.tile = 0;
  expect_inside_found_whole(detect_in_tiles(white_rectangles, image, plan, 0.5f));
}

TEST(TiledDetection, WholeImageOnlyWithoutTiles) {
  cv::Mat image(200, 300, CV_8UC3, cv::Scalar(0, 0, 0));
  cv::rectangle(image, cv::Rect(10, 10, 50, 50), cv::Scalar(255, 255, 255), cv::FILLED);
  int calls = 0;
  const auto counting = [&](const cv::Mat& tile) {
    ++calls;
    EXPECT_EQ(tile.size(), image.size());
    return white_rectangles(tile);
  };
  EXPECT_EQ(detect_in_tiles(counting, image, TilingPlan{}, 0.5f).size(), 1u);
  EXPECT_EQ(calls, 1);
}

TEST(TiledDetection, FixedTilesOverlapByAQuarterAndMustFit) {
  const TilingPlan plan = fixed_tiling(320);
  EXPECT_EQ(plan.tile, 320);
  EXPECT_EQ(plan.stride, 240);
  EXPECT_EQ(fixed_tiling(0).tile, 0);  // the whole image
  EXPECT_EQ(fixed_tiling(1).stride, 1);
  // 640 x 480 in 320-pixel tiles: three columns (0, 160, 320), two rows (0, 160).
  EXPECT_EQ(detection_tiles({640, 480}, plan).size(), 6u);
  EXPECT_TRUE(tile_fits({640, 480}, 480));
  EXPECT_FALSE(tile_fits({640, 480}, 481));  // wider than the image is tall
  EXPECT_FALSE(tile_fits({300, 700}, 301));
  EXPECT_TRUE(tile_fits({300, 700}, 0));
}

}  // namespace
}  // namespace flexsight

// The depth segmentation on a small simulated bin (`flexsight synth bin`, 320 x 240) with
// its ground-truth depth: the regions' boxes match (IoU 0.5) most parts at least half
// visible. The measured depth's figures on the full-size bins are in docs/pick.md.
#include <gtest/gtest.h>

#include <algorithm>

#include "host/dataset/bop_reader.h"
#include "host/render/mesh.h"
#include "host/segment/depth_segmentation.h"
#include "tests/cli/cli_test_support.h"

namespace flexsight {
namespace {

using namespace cli_test_support;

double iou(const cv::Rect& a, const cv::Rect& b) {
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter);
}

TEST(DepthSegmentationOnABin, BoxesCoverMostHalfVisibleParts) {
  const fs::path dir = fresh_temp_dir("DepthSegmentationOnABin");
  const std::string cad = FLEXSIGHT_TLESS_CAD_DIR;
  const RunResult run = run_flexsight(
      "synth bin --count 1 --seed 3 --size 320x240 --cad " + cad + " -o " + (dir / "bins").string(), dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const BopReader reader((dir / "bins" / "bin000").string());
  const AnnotatedImage image = reader.load(0);
  ASSERT_FALSE(image.depth.empty());

  // The part sizes pick would give: the smallest and largest diameter of the CAD folder.
  DepthSegmentationOptions options;
  options.smallest_part_mm = 1e9;
  for (const auto& entry : fs::directory_iterator(cad)) {
    if (entry.path().extension() != ".stl") continue;
    const double diameter = load_mesh(entry.path().string()).diameter;
    options.smallest_part_mm = std::min(options.smallest_part_mm, diameter);
    options.largest_part_mm = std::max(options.largest_part_mm, diameter);
  }
  PinholeCamera camera;
  camera.fx = image.camera.K(0, 0), camera.fy = image.camera.K(1, 1);
  camera.cx = image.camera.K(0, 2), camera.cy = image.camera.K(1, 2);
  camera.width = image.depth.cols, camera.height = image.depth.rows;
  const DepthSegmentation segmentation = segment_depth(image.depth, camera, options);
  ASSERT_TRUE(segmentation.floor.found);

  int targets = 0, found = 0;
  for (const PartAnnotation& part : image.parts) {
    if (part.visib_fract < 0.5 || part.bbox_visib.empty()) continue;
    ++targets;
    const cv::Rect truth(part.bbox_visib.x, part.bbox_visib.y, part.bbox_visib.width, part.bbox_visib.height);
    const bool matched = std::any_of(segmentation.regions.begin(), segmentation.regions.end(),
                                     [&](const DepthRegion& r) { return iou(r.box, truth) >= 0.5; });
    found += matched;
  }
  ASSERT_GE(targets, 5);
  EXPECT_GE(found, targets / 2 + 1) << found << " of " << targets << " parts found";
  // No more boxes than a few per part: the regions are parts, not speckles.
  EXPECT_LE(segmentation.regions.size(), 2u * image.parts.size());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace flexsight

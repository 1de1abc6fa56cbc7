// The bin's region from a coarse disparity (host/pick/bin_region.h), on a synthetic
// disparity: a table facing the camera, a bin standing on it (its floor 20 mm higher,
// walls whose rims are 100 mm higher), a part on the floor. The region is the bin's
// rectangle (grown by the margin) and its range runs from the floor to the rims; the
// table is left out.
#include "host/pick/bin_region.h"

#include <gtest/gtest.h>

#include <cmath>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

// f = 1000 px, baseline 100 mm, no disparity offset: Z = 1e5 / d (mm).
StereoCamera test_rig(int width, int height) {
  StereoCamera rig;
  rig.Q = reprojection_matrix(1000.0, width / 2.0, height / 2.0, width / 2.0, 100.0);
  rig.width = width;
  rig.height = height;
  return rig;
}

float disparity_at_depth(double z_mm) { return static_cast<float>(1e5 / z_mm); }

struct SyntheticBin {
  cv::Mat disparity;
  cv::Rect bin{100, 70, 160, 110};  // outer walls
  float floor = disparity_at_depth(980.0);
  float rim = disparity_at_depth(880.0);
};

SyntheticBin synthetic_bin() {
  SyntheticBin s;
  s.disparity = cv::Mat(240, 320, CV_32FC1, cv::Scalar(disparity_at_depth(1000.0)));  // the table
  s.disparity(s.bin).setTo(s.rim);
  s.disparity(cv::Rect(s.bin.x + 6, s.bin.y + 6, s.bin.width - 12, s.bin.height - 12)).setTo(s.floor);
  s.disparity(cv::Rect(150, 100, 30, 20)).setTo(disparity_at_depth(940.0));  // a part
  return s;
}

TEST(BinRegion, IsTheBinsRectangleAndRunsFromItsFloorToItsRims) {
  const SyntheticBin s = synthetic_bin();
  const BinRegionOptions options;
  const BinRegion region = find_bin_region(s.disparity, test_rig(320, 240), 200, options);
  ASSERT_TRUE(region.found);
  const int m = options.rect_margin_px;
  const cv::Rect grown(s.bin.x - m, s.bin.y - m, s.bin.width + 2 * m, s.bin.height + 2 * m);
  EXPECT_EQ(region.rect, grown);
  EXPECT_EQ(region.range.min, static_cast<int>(std::floor(s.floor)) - options.disparity_margin);
  EXPECT_EQ(region.range.max, static_cast<int>(std::ceil(s.rim)) + options.disparity_margin);
  // The floor fitted is the bin's, not the table under it.
  EXPECT_NEAR(-region.floor.offset / region.floor.normal.z(), 980.0, 3.0);
}

TEST(BinRegion, TheRangeNeverExceedsThePairsSearchRange) {
  const SyntheticBin s = synthetic_bin();
  const BinRegion region = find_bin_region(s.disparity, test_rig(320, 240), 110);
  ASSERT_TRUE(region.found);
  EXPECT_EQ(region.range.max, 109);
}

TEST(BinRegion, WithoutAFloorIsTheWholeImageAndRange) {
  const cv::Mat nothing(240, 320, CV_32FC1, cv::Scalar(NAN));
  const BinRegion region = find_bin_region(nothing, test_rig(320, 240), 64);
  EXPECT_FALSE(region.found);
  EXPECT_EQ(region.rect, cv::Rect(0, 0, 320, 240));
  EXPECT_EQ(region.range.min, 0);
  EXPECT_EQ(region.range.max, 63);
}

TEST(BinRegion, ImpossibleOptionsAreRefused) {
  BinRegionOptions options;
  options.opening_px = 0;
  EXPECT_THROW(find_bin_region(synthetic_bin().disparity, test_rig(320, 240), 64, options), InputError);
}

}  // namespace
}  // namespace flexsight

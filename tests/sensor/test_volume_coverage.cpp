// Coverage of the working volume (host/sensor/volume_coverage.h) on hand-made rigs whose
// frustums cut the volume where we choose.
#include <gtest/gtest.h>

#include <cmath>

#include "host/sensor/volume_coverage.h"

namespace flexsight {
namespace {

constexpr double kPi = 3.14159265358979323846;

// f = 1000 px on 1000 x 800 images, baseline 100 mm, a 90 x 90 degree projector: at 1 m
// each camera sees a 1000 x 800 mm window, so a 200 mm box there is well inside.
StereoRig wide_rig(double doffs = 0.0, double baseline = 100.0, const Projector& projector = {0.0, 90.0, 90.0}) {
  return make_centred_stereo_rig(baseline, 1000, 800, 1000.0, doffs, projector);
}

WorkingVolume box(double width, double height, double depth, double distance) {
  WorkingVolume v;
  v.width = width;
  v.height = height;
  v.depth = depth;
  v.distance = distance;
  return v;
}

TEST(SensorCoverage, VolumeInsideAllFrustumsIsFullyCovered) {
  const VolumeCoverage c = measure_coverage(wide_rig(), box(200, 200, 200, 1000), 10.0);
  EXPECT_EQ(c.volume.samples, 20 * 20 * 20);
  EXPECT_DOUBLE_EQ(c.volume.all, 100.0);
  EXPECT_FALSE(c.any_unseen);
  ASSERT_EQ(c.faces.size(), 6u);
  for (const RegionCoverage& f : c.faces) EXPECT_DOUBLE_EQ(f.all, 100.0) << f.name;
  for (const CornerCoverage& k : c.corners) EXPECT_EQ(k.seen, unsigned(kSeenByAll)) << k.name;
  EXPECT_EQ(cv::countNonZero(c.top_unseen), 0);
}

TEST(SensorCoverage, VolumeHalfOutsideOneCameraIsAboutHalfCoveredByIt) {
  // cx_left = 950: the left camera's right image border is the plane x = -50 + z / 20,
  // which crosses x = 0 at the volume's centroid (z = 1000); the box is thin in z, so
  // that plane halves it. The right camera mirrors it (x >= 0).
  const StereoRig r = wide_rig(-900.0);  // cx_left = 500 + 450, cx_right = 500 - 450
  const VolumeCoverage c = measure_coverage(r, box(200, 200, 40, 1000), 5.0);
  EXPECT_NEAR(c.volume.left, 50.0, 1.0);
  EXPECT_NEAR(c.volume.right, 50.0, 1.0);
  EXPECT_DOUBLE_EQ(c.volume.projector, 100.0);
  EXPECT_NEAR(c.volume.cameras, 0.0, 1.0);
  // The left face is seen by the left camera only, the right face by the right camera.
  EXPECT_DOUBLE_EQ(c.faces[2].left, 100.0);
  EXPECT_DOUBLE_EQ(c.faces[2].right, 0.0);
  EXPECT_DOUBLE_EQ(c.faces[3].left, 0.0);
  EXPECT_DOUBLE_EQ(c.faces[3].right, 100.0);
}

TEST(SensorCoverage, VolumeHalfOutsideTheProjectorIsHalfCovered) {
  // Cameras at x = +-200 (they still see the whole box) and a projector at x = 100 whose
  // frustum edge x = 100 - z / 10 crosses x = 0 at 1 m and whose other edge
  // (x = 100 + z / 10) lies beyond the box: it lights x >= 0 only.
  const StereoRig r = wide_rig(0.0, 400.0, {100.0, 2.0 * std::atan(0.1) * 180.0 / kPi, 90.0});
  const VolumeCoverage c = measure_coverage(r, box(200, 200, 40, 1000), 5.0);
  EXPECT_DOUBLE_EQ(c.volume.cameras, 100.0);
  EXPECT_NEAR(c.volume.projector, 50.0, 1.0);
  EXPECT_NEAR(c.volume.all, 50.0, 1.0);
  EXPECT_TRUE(c.any_unseen);
  EXPECT_LT(c.unseen_max.x(), 1.0);  // the unseen samples are on the x < 0 side
  EXPECT_DOUBLE_EQ(c.faces[2].all, 0.0);    // left face: dark
  EXPECT_DOUBLE_EQ(c.faces[3].all, 100.0);  // right face: lit
}

TEST(SensorCoverage, FrustumsWideningWithDepthLoseTheNearPlaneFirst) {
  // f = 4000 px on 2000 px: each camera sees x within +-z / 4 of its centre, so both see
  // |x| <= z / 4 - 50: 150 mm at the near plane (800) and 250 mm at the far one (1200).
  // The 400 mm wide box is cut at its near end and whole at its far end.
  const StereoRig r = make_centred_stereo_rig(100.0, 2000, 4000, 4000.0, 0.0, {0.0, 90.0, 90.0});
  const VolumeCoverage c = measure_coverage(r, box(400, 100, 400, 1000), 10.0, 4);
  ASSERT_EQ(c.slabs.size(), 4u);
  for (size_t s = 1; s < c.slabs.size(); ++s) EXPECT_GE(c.slabs[s].all, c.slabs[s - 1].all);
  EXPECT_LT(c.faces[0].all, c.faces[1].all);  // near < far
  EXPECT_DOUBLE_EQ(c.faces[1].all, 100.0);
  // Near top left (-200, -50, 800): the left camera sees it, the right one does not.
  EXPECT_EQ(c.corners[0].seen, unsigned(kSeenByLeft | kSeenByProjector));
  EXPECT_EQ(c.corners[1].seen, unsigned(kSeenByRight | kSeenByProjector));
  EXPECT_EQ(c.corners[4].seen, unsigned(kSeenByAll));
  EXPECT_GT(c.volume.all, 50.0);
  EXPECT_LT(c.volume.all, 100.0);
}

}  // namespace
}  // namespace flexsight

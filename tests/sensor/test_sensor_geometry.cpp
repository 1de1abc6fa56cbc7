// The sensor planner's maths on hand-made cases (host/sensor/sensor_geometry.h,
// sensor_plan.h): disparity with doffs, the depth step, fields of view, the fitting focal
// length and the centring doffs.
#include <gtest/gtest.h>

#include <cmath>

#include "host/sensor/sensor_geometry.h"
#include "host/sensor/sensor_plan.h"

namespace flexsight {
namespace {

StereoRig rig(double focal, double baseline, double doffs) {
  return make_centred_stereo_rig(baseline, 1000, 800, focal, doffs, Projector{});
}

bool project_left(const StereoRig& r, const Eigen::Vector3d& p, double& u, double& v) {
  return project_from(r.left, r.left_centre_x(), p, u, v);
}
bool project_right(const StereoRig& r, const Eigen::Vector3d& p, double& u, double& v) {
  return project_from(r.right, r.right_centre_x(), p, u, v);
}
bool left_sees(const StereoRig& r, const Eigen::Vector3d& p) { return camera_sees(r.left, r.left_centre_x(), p); }
bool right_sees(const StereoRig& r, const Eigen::Vector3d& p) { return camera_sees(r.right, r.right_centre_x(), p); }

TEST(SensorGeometry, OnAxisPointHasDisparityFocalBaselineOverDepthMinusDoffs) {
  const StereoRig r = rig(1200.0, 100.0, 25.0);
  for (double z : {500.0, 1000.0, 3000.0}) {
    const Eigen::Vector3d p(0.0, 0.0, z);
    double ul = 0, vl = 0, ur = 0, vr = 0;
    ASSERT_TRUE(project_left(r, p, ul, vl));
    ASSERT_TRUE(project_right(r, p, ur, vr));
    EXPECT_NEAR(ul - ur, 1200.0 * 100.0 / z - 25.0, 1e-9);
    EXPECT_NEAR(r.disparity(z), 1200.0 * 100.0 / z - 25.0, 1e-12);
    EXPECT_DOUBLE_EQ(vl, vr);  // rectified: same row
    // Middlebury's triangulation takes it back: Z = f B / (d + doffs).
    EXPECT_NEAR(1200.0 * 100.0 / (r.disparity(z) + 25.0), z, 1e-9);
  }
  // Off-axis points too: disparity depends on depth only.
  double ul = 0, vl = 0, ur = 0, vr = 0;
  ASSERT_TRUE(project_left(r, {-300.0, 77.0, 800.0}, ul, vl));
  ASSERT_TRUE(project_right(r, {-300.0, 77.0, 800.0}, ur, vr));
  EXPECT_NEAR(ul - ur, r.disparity(800.0), 1e-9);
}

TEST(SensorGeometry, DepthStepIsDepthSquaredTimesStepOverFocalBaseline) {
  EXPECT_DOUBLE_EQ(depth_step(1000.0, 1000.0, 100.0, 1.0), 10.0);
  EXPECT_DOUBLE_EQ(depth_step(2000.0, 1000.0, 100.0, 1.0), 40.0);  // quadratic in Z
  EXPECT_DOUBLE_EQ(depth_step(1000.0, 1000.0, 100.0, 0.25), 2.5);
  // It is the change of Z = f B / d over one disparity step, to first order.
  const double f = 7000.0, b = 500.0, z = 1450.0, d = f * b / z, step = 1.0 / 16.0;
  EXPECT_NEAR(f * b / (d - step) - z, depth_step(z, f, b, step), 1e-4);
  // Solved for the focal length or the step, it gives the step back.
  EXPECT_NEAR(depth_step(z, focal_for_depth_step(z, 0.3, b, 0.5), b, 0.5), 0.3, 1e-12);
  EXPECT_NEAR(depth_step(z, f, b, subpixel_for_depth_step(z, 0.3, f, b)), 0.3, 1e-12);
}

TEST(SensorGeometry, FieldOfViewAndFocalLengthAreInverse) {
  EXPECT_NEAR(focal_from_hfov(90.0, 2000), 1000.0, 1e-9);
  EXPECT_NEAR(hfov_from_focal(1000.0, 2000), 90.0, 1e-9);
  EXPECT_NEAR(hfov_from_focal(focal_from_hfov(35.0, 4000), 4000), 35.0, 1e-9);
}

TEST(SensorGeometry, FittingFocalMakesTheNearFaceSpanTheImage) {
  // The paper's volume: the near face (600 mm at 1050 mm) spans the 4000 px width, since
  // both cameras lie within the volume's x range.
  WorkingVolume v;
  EXPECT_NEAR(fitting_focal(500.0, v, 4000, 3000), 4000.0 * 1050.0 / 600.0, 1e-9);
  // The centring doffs of a volume whose near face decides: f B / Z_near.
  EXPECT_NEAR(centring_doffs(7000.0, 500.0, v), 7000.0 * 500.0 / 1050.0, 1e-9);
  // With that focal length and doffs the corners land on the image borders.
  const StereoRig r = make_centred_stereo_rig(500.0, 4000, 3000, 7000.0, centring_doffs(7000.0, 500.0, v), Projector{});
  double u = 0, vv = 0;
  ASSERT_TRUE(project_left(r, v.corner(0), u, vv));  // near top left
  EXPECT_NEAR(u, 0.0, 1e-6);
  ASSERT_TRUE(project_left(r, v.corner(1), u, vv));  // near top right
  EXPECT_NEAR(u, 4000.0, 1e-6);
  for (int c = 0; c < 8; ++c) {
    EXPECT_TRUE(left_sees(r, v.corner(c))) << c;
    EXPECT_TRUE(right_sees(r, v.corner(c))) << c;
  }
  // A tall volume is limited by the height instead.
  WorkingVolume tall;
  tall.height = 1200.0;
  EXPECT_NEAR(fitting_focal(500.0, tall, 4000, 3000), 1500.0 * 1050.0 / 600.0, 1e-9);
}

TEST(SensorGeometry, PointsBehindTheSensorAreNotSeen) {
  const StereoRig r = rig(1000.0, 100.0, 0.0);
  EXPECT_FALSE(left_sees(r, {0.0, 0.0, -100.0}));
  EXPECT_FALSE(left_sees(r, {0.0, 0.0, 0.0}));
  EXPECT_FALSE(r.projector.sees({0.0, 0.0, -100.0}));
  EXPECT_TRUE(r.projector.sees({0.0, 0.0, 100.0}));
  // The projector's 35 degree frustum: tan(17.5 deg) = 0.3153.
  EXPECT_TRUE(r.projector.sees({31.0, 31.0, 100.0}));
  EXPECT_FALSE(r.projector.sees({32.0, 0.0, 100.0}));
  EXPECT_FALSE(r.projector.sees({0.0, 32.0, 100.0}));
}

TEST(SensorPlan, PaperCameraFigures) {
  const SensorPlan plan = make_sensor_plan(SensorPlanInputs{});
  EXPECT_TRUE(plan.focal_fitted);
  EXPECT_NEAR(plan.rig.focal(), 7000.0, 1e-6);
  EXPECT_NEAR(plan.coverage.volume.all, 100.0, 1e-12);
  const double fb = 7000.0 * 500.0;
  EXPECT_NEAR(plan.dz_near_mm, 1050.0 * 1050.0 / 16.0 / fb, 1e-12);
  EXPECT_NEAR(plan.dz_far_mm, 1450.0 * 1450.0 / 16.0 / fb, 1e-12);
  EXPECT_NEAR(plan.raw_disparity_near, fb / 1050.0, 1e-9);
  EXPECT_NEAR(plan.raw_disparity_far, fb / 1450.0, 1e-9);
  EXPECT_NEAR(plan.disparity_near, 0.0, 1e-9);  // centring doffs = f B / Z_near
  EXPECT_NEAR(plan.disparity_far, fb / 1450.0 - fb / 1050.0, 1e-9);
  EXPECT_EQ(plan.ndisp, 921);  // -919.5 .. 0 shifted by 920
  // 0.3 mm at 1450 mm with f = 7000 px needs a half-pixel disparity step.
  EXPECT_NEAR(plan.subpixel_for_target, 0.3 * fb / (1450.0 * 1450.0), 1e-12);
  EXPECT_NEAR(plan.subpixel_for_target, 0.4994, 1e-4);
  EXPECT_NEAR(plan.focal_for_target_1px, 1450.0 * 1450.0 / (0.3 * 500.0), 1e-9);
}

}  // namespace
}  // namespace flexsight

// Plane algebra: transfer between views, carrying to a finer level, perturbation.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/stereo/pms_math.h"

TEST(PlaneMath, DisparityOfPlane) {
  EXPECT_FLOAT_EQ(pms_plane_disparity(0.5f, -0.25f, 10.0f, 4.0f, 8.0f), 10.0f);
}

TEST(PlaneMath, TransferMapsCorrespondingPointsToTheSameDisparity) {
  const float left[3] = {0.1f, -0.05f, 20.0f};
  float right[3];
  ASSERT_TRUE(pms_transfer_plane(left, PMS_VIEW_LEFT, right));
  for (float x : {10.0f, 57.0f, 130.0f}) {
    for (float y : {0.0f, 33.0f}) {
      float d = pms_plane_disparity(left[0], left[1], left[2], x, y);
      // The left point (x, y) sees the right point (x - d, y) with the same disparity.
      EXPECT_NEAR(pms_plane_disparity(right[0], right[1], right[2], x - d, y), d, 1e-4f);
    }
  }
}

TEST(PlaneMath, TransferThereAndBackIsTheIdentity) {
  const float left[3] = {-0.2f, 0.3f, 12.5f};
  float right[3], back[3];
  ASSERT_TRUE(pms_transfer_plane(left, PMS_VIEW_LEFT, right));
  ASSERT_TRUE(pms_transfer_plane(right, PMS_VIEW_RIGHT, back));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], left[i], 1e-5f);
}

TEST(PlaneMath, TransferRejectsPlanesTooSteepToSee) {
  const float steep[3] = {0.99f, 0.0f, 1.0f};
  float out[3] = {42, 42, 42};
  EXPECT_FALSE(pms_transfer_plane(steep, PMS_VIEW_LEFT, out));
  EXPECT_EQ(out[0], 42.0f);
}

TEST(PlaneMath, CarryToFinerDoublesDisparityAtTheCoarsePixelCentre) {
  const float coarse[3] = {0.2f, -0.1f, 7.0f};
  float fine[3];
  pms_carry_plane_to_finer(coarse, fine);
  EXPECT_EQ(fine[0], coarse[0]);
  EXPECT_EQ(fine[1], coarse[1]);
  for (int X : {0, 5, 40}) {
    for (int Y : {0, 9}) {
      // Coarse pixel X covers fine pixels 2X and 2X + 1, centre 2X + 0.5.
      float expected = 2.0f * pms_plane_disparity(coarse[0], coarse[1], coarse[2], X, Y);
      EXPECT_NEAR(pms_plane_disparity(fine[0], fine[1], fine[2], 2 * X + 0.5f, 2 * Y + 0.5f),
                  expected, 1e-4f);
    }
  }
}

TEST(PlaneMath, FrontoParallelCarryIsExactDoubling) {
  const float coarse[3] = {0.0f, 0.0f, 13.25f};
  float fine[3];
  pms_carry_plane_to_finer(coarse, fine);
  EXPECT_EQ(fine[2], 26.5f);
}

TEST(PlaneMath, PerturbationStaysWithinItsRanges) {
  const float plane[3] = {0.1f, 0.05f, 3.0f};
  const int x = 20, y = 30;
  const float d0 = pms_plane_disparity(plane[0], plane[1], plane[2], x, y);
  int accepted = 0;
  for (fs_u32 i = 0; i < 2000; ++i) {
    float u[4];
    for (int c = 0; c < 4; ++c) u[c] = pms_random_unit(3, 0, i, 1, c);
    float out[3];
    if (!pms_perturb_plane(plane, x, y, 63.0f, 4.0f, 0.25f, u[0], u[1], u[2], u[3], out)) continue;
    ++accepted;
    float d = pms_plane_disparity(out[0], out[1], out[2], x, y);
    EXPECT_LE(std::fabs(d - d0), 4.0f + 1e-4f);
    EXPECT_GE(d, -1e-4f);
    // Normal (-a, -b, 1) normalised moved by at most 0.25 per component before
    // renormalisation: the slopes cannot move far for a near-frontal plane.
    EXPECT_LT(std::fabs(out[0] - plane[0]), 0.8f);
    EXPECT_LT(std::fabs(out[1] - plane[1]), 0.8f);
  }
  EXPECT_GT(accepted, 1900);  // a near-frontal plane is rarely pushed past the limit
}

TEST(PlaneMath, PerturbationClampsToTheDisparityRange) {
  const float plane[3] = {0.0f, 0.0f, 62.5f};
  float out[3];
  ASSERT_TRUE(pms_perturb_plane(plane, 0, 0, 63.0f, 10.0f, 0.0f, 0.999f, 0.5f, 0.5f, 0.5f, out));
  EXPECT_FLOAT_EQ(pms_plane_disparity(out[0], out[1], out[2], 0, 0), 63.0f);
}

TEST(PlaneMath, SpatialCandidatesAreOnTheOtherParity) {
  for (int c = 0; c < PMS_SPATIAL_CANDIDATES; ++c) {
    int dx = 0, dy = 0;
    pms_spatial_offset(c, &dx, &dy);
    EXPECT_EQ((std::abs(dx) + std::abs(dy)) % 2, 1) << "candidate " << c;
  }
}

TEST(PlaneMath, SearchScheduleHalvesDownToTheMinimum) {
  EXPECT_EQ(pms_search_trial_count(32.0f, 0.25f), 8);  // 32 16 8 4 2 1 0.5 0.25
  EXPECT_EQ(pms_search_trial_count(0.1f, 0.25f), 0);
}

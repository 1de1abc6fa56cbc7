// PPMS's confidence rule for spatial propagation in the reference path
// (fallback/stereo/patchmatch_reference.cpp): a confident pixel tries only the nearest
// confident_spatial_candidates neighbours. The OpenCL tests prove the kernel gives the
// same bytes; these pin what the rule does.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "tests/stereo/kernel_cases.h"

using namespace flexsight;
using namespace flexsight::testing_support;

namespace {

const LevelCase kCase{64, 48, 11, 2, 16, 3};

bool same_plane(const float* a, const float* b) { return std::memcmp(a, b, 3 * sizeof(float)) == 0; }

TEST(SpatialConfidenceRule, PixelsBelowTheThresholdTryEveryCandidate) {
  ReferenceLevel without(kCase);
  ReferenceLevel unsure(kCase);
  SearchSchedule schedule = search_schedule(kCase.ndisp);
  schedule.confident_spatial_candidates = 0;
  const std::vector<float> confidence(without.fields[0].pixels(),
                                      schedule.confident_threshold * 0.99f);
  for (int parity = 0; parity < 2; ++parity) {
    propagate_spatial(without.in, PMS_VIEW_LEFT, parity, schedule, nullptr,
                      without.fields[PMS_VIEW_LEFT]);
    propagate_spatial(unsure.in, PMS_VIEW_LEFT, parity, schedule, &confidence,
                      unsure.fields[PMS_VIEW_LEFT]);
  }
  EXPECT_EQ(without.fields[PMS_VIEW_LEFT].planes, unsure.fields[PMS_VIEW_LEFT].planes);
  EXPECT_EQ(without.fields[PMS_VIEW_LEFT].cost, unsure.fields[PMS_VIEW_LEFT].cost);
}

TEST(SpatialConfidenceRule, ConfidentPixelsWithNoCandidatesKeepTheirPlanes) {
  ReferenceLevel f(kCase);
  SearchSchedule schedule = search_schedule(kCase.ndisp);
  schedule.confident_spatial_candidates = 0;
  const std::vector<float> confidence(f.fields[0].pixels(), schedule.confident_threshold);
  const PlaneField before = f.fields[PMS_VIEW_LEFT];
  for (int parity = 0; parity < 2; ++parity) {
    propagate_spatial(f.in, PMS_VIEW_LEFT, parity, schedule, &confidence,
                      f.fields[PMS_VIEW_LEFT]);
  }
  EXPECT_EQ(before.planes, f.fields[PMS_VIEW_LEFT].planes);
  EXPECT_EQ(before.cost, f.fields[PMS_VIEW_LEFT].cost);
}

// With the first ring only, a confident pixel that changed took the plane of one of its
// four direct neighbours (one parity, so the neighbours are not written meanwhile);
// unsure pixels also reach farther, which the test checks too, so that it cannot pass
// on a field where nothing moved.
TEST(SpatialConfidenceRule, ConfidentPixelsTakePlanesOnlyFromTheNearestRing) {
  ReferenceLevel f(kCase);
  SearchSchedule schedule = search_schedule(kCase.ndisp);
  schedule.confident_spatial_candidates = 4;
  const PlaneField& field = f.fields[PMS_VIEW_LEFT];
  const int width = field.width;
  const int height = field.height;
  std::vector<float> confidence(field.pixels());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) confidence[y * width + x] = x < width / 2 ? 1.0f : 0.0f;
  }
  const PlaneField before = field;
  propagate_spatial(f.in, PMS_VIEW_LEFT, 0, schedule, &confidence, f.fields[PMS_VIEW_LEFT]);

  int confident_changed = 0;
  int unsure_from_far = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = (y & 1); x < width; x += 2) {  // parity 0: (x + y) even
      const float* now = &field.planes[4 * (y * width + x)];
      if (same_plane(now, &before.planes[4 * (y * width + x)])) continue;
      bool from_ring_one = false;
      for (int candidate = 0; candidate < 4; ++candidate) {
        int dx = 0;
        int dy = 0;
        pms_spatial_offset(candidate, &dx, &dy);
        const int nx = x + dx;
        const int ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
        from_ring_one |= same_plane(now, &before.planes[4 * (ny * width + nx)]);
      }
      if (confidence[y * width + x] >= schedule.confident_threshold) {
        ++confident_changed;
        EXPECT_TRUE(from_ring_one) << "confident pixel (" << x << ", " << y << ")";
      } else {
        unsure_from_far += from_ring_one ? 0 : 1;
      }
    }
  }
  EXPECT_GT(confident_changed, 0);
  EXPECT_GT(unsure_from_far, 0);
}

}  // namespace

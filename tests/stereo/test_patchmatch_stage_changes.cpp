// The PatchMatch stages of fallback/stereo/patchmatch_reference.cpp change planes on the
// stage cases of tests/stereo/kernel_cases.h, run as the OpenCL stage tests run them
// (tests/stereo/opencl/test_opencl_patchmatch_stages.cpp): those compare each kernel with
// its reference stage byte for byte, which proves little where the stage keeps every
// plane. Every view and parity must change some plane, on every case with room to: the
// 1x1 and 7x5 cases are left out, there the window covers the image, the candidates'
// costs tie and a stage may rightly keep every plane.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

#include "tests/stereo/kernel_cases.h"

namespace flexsight::testing_support {
namespace {

std::vector<LevelCase> cases_with_room_to_change() {
  std::vector<LevelCase> cases;
  const std::vector<LevelCase> all = level_cases();
  std::copy_if(all.begin(), all.end(), std::back_inserter(cases),
               [](const LevelCase& c) { return c.width * c.height >= 500; });
  return cases;
}

class PatchMatchReferenceStage : public ::testing::TestWithParam<LevelCase> {};

// Runs `stage(level, view, parity)` on a copy of each view's field and expects a plane
// changed, for both views and parities; the field then carries the change on, as in the
// OpenCL tests.
template <class Stage>
void expect_every_call_changes_planes(ReferenceLevel& f, Stage stage) {
  for (int view = 0; view < 2; ++view) {
    for (int parity = 0; parity < 2; ++parity) {
      const PlaneField before = f.fields[view];
      stage(view, parity);
      EXPECT_NE(before.planes, f.fields[view].planes)
          << "view " << view << ", parity " << parity << ": the stage changed no plane";
    }
  }
}

TEST_P(PatchMatchReferenceStage, PropagateSpatialWithoutConfidence) {
  ReferenceLevel f(GetParam());
  const SearchSchedule schedule = search_schedule(f.in.ndisp);
  expect_every_call_changes_planes(f, [&](int view, int parity) {
    propagate_spatial(f.in, view, parity, schedule, nullptr, f.fields[view]);
  });
}

TEST_P(PatchMatchReferenceStage, PropagateSpatialWithConfidence) {
  ReferenceLevel f(GetParam());
  SearchSchedule schedule = search_schedule(f.in.ndisp);
  schedule.confident_spatial_candidates =
      1 + static_cast<int>(GetParam().seed % PMS_SPATIAL_CANDIDATES);
  const std::vector<float> confidence = random_confidence(f.fields[0].pixels(), GetParam().seed);
  expect_every_call_changes_planes(f, [&](int view, int parity) {
    propagate_spatial(f.in, view, parity, schedule, &confidence, f.fields[view]);
  });
}

TEST_P(PatchMatchReferenceStage, PropagateView) {
  ReferenceLevel f(GetParam());
  advance(f);
  expect_every_call_changes_planes(f, [&](int view, int parity) {
    propagate_view(f.in, view, parity, SearchSchedule{}, nullptr, f.fields[1 - view],
                   f.fields[view]);
  });
}

TEST_P(PatchMatchReferenceStage, UnsurePixelsOnly) {
  ReferenceLevel f(GetParam());
  advance(f);
  SearchSchedule schedule = search_schedule(f.in.ndisp);
  schedule.unsure_only = true;
  const std::vector<float> confidence = random_confidence(f.fields[0].pixels(), GetParam().seed);
  expect_every_call_changes_planes(f, [&](int view, int parity) {
    propagate_spatial(f.in, view, parity, schedule, &confidence, f.fields[view]);
    propagate_view(f.in, view, parity, schedule, &confidence, f.fields[1 - view], f.fields[view]);
    refine_random(f.in, view, parity, 9, schedule, &confidence, f.fields[view]);
  });
}

TEST_P(PatchMatchReferenceStage, RefineRandomWithoutConfidence) {
  ReferenceLevel f(GetParam());
  advance(f);
  const SearchSchedule schedule = search_schedule(f.in.ndisp);
  expect_every_call_changes_planes(f, [&](int view, int parity) {
    refine_random(f.in, view, parity, 5, schedule, nullptr, f.fields[view]);
  });
}

TEST_P(PatchMatchReferenceStage, RefineRandomWithConfidence) {
  ReferenceLevel f(GetParam());
  advance(f);
  const SearchSchedule schedule = search_schedule(f.in.ndisp);
  const std::vector<float> confidence = random_confidence(f.fields[0].pixels(), GetParam().seed);
  expect_every_call_changes_planes(f, [&](int view, int parity) {
    refine_random(f.in, view, parity, 70, schedule, &confidence, f.fields[view]);
  });
}

INSTANTIATE_TEST_SUITE_P(Cases, PatchMatchReferenceStage,
                         ::testing::ValuesIn(cases_with_room_to_change()),
                         [](const ::testing::TestParamInfo<LevelCase>& info) {
                           return case_name(info.param);
                         });

}  // namespace
}  // namespace flexsight::testing_support

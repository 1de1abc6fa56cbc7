// Every PatchMatch stage kernel against its function of fallback/stereo/patchmatch_reference.cpp
// on the same inputs (tests/stereo/kernel_cases.h, which the benchmarks time too), byte for
// byte, with a guard region after every output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <utility>
#include <memory>
#include <stdexcept>
#include <tuple>

#include "tests/stereo/opencl/opencl_test_support.h"

namespace flexsight::opencl::test {
namespace {

// That the reference stages change planes on these cases (so that the comparisons below
// compare work done) is checked apart, without a device, in
// tests/stereo/test_patchmatch_stage_changes.cpp.
class PatchMatchStage : public ::testing::TestWithParam<LevelCase> {};

TEST_P(PatchMatchStage, InitRandomPlanes) {
  LevelFixture f(GetParam());
  for (int view = 0; view < 2; ++view) {
    const size_t pixels = f.fields[view].pixels();
    DeviceField field{f.fields[view].width, f.fields[view].height,
                      guarded_output<float>(4 * pixels, "planes"),
                      guarded_output<float>(pixels, "cost")};
    stages().init_random_planes(f.device_in, view, 0, field);
    expect_same_field(f.fields[view], field);
  }
}

TEST_P(PatchMatchStage, EvaluateCosts) {
  LevelFixture f(GetParam());
  advance(f);
  for (int view = 0; view < 2; ++view) {
    PlaneField expected = f.fields[view];
    evaluate_costs(f.in, view, expected);
    DeviceField field{expected.width, expected.height, guarded(f.fields[view].planes, "planes"),
                      guarded_output<float>(expected.pixels(), "cost")};
    stages().evaluate_costs(f.device_in, view, field);
    expect_same_field(expected, field);
  }
}

// After the filling only the filled pixels' planes change: the others keep their cost
// bytes (here a marker no cost can be), the filled ones get their plane's full cost.
TEST_P(PatchMatchStage, EvaluateCostsOfChangedPixelsOnly) {
  const LevelCase c = GetParam();
  LevelFixture f(c);
  advance(f);
  const std::vector<std::uint8_t> unchanged = random_consistency(c.width, c.height, c.seed);
  for (int view = 0; view < 2; ++view) {
    PlaneField full = f.fields[view];
    evaluate_costs(f.in, view, full);
    PlaneField expected = f.fields[view];
    std::fill(expected.cost.begin(), expected.cost.end(), -1.0f);
    const PlaneField before = expected;
    evaluate_costs(f.in, view, expected, &unchanged);
    for (size_t i = 0; i < unchanged.size(); ++i) {
      const float want = unchanged[i] ? -1.0f : full.cost[i];
      ASSERT_EQ(std::memcmp(&expected.cost[i], &want, sizeof want), 0) << "pixel " << i;
    }
    DeviceField field = upload(before, "field");
    const Buffer<std::uint8_t> device_unchanged = guarded(unchanged, "unchanged");
    stages().evaluate_costs(f.device_in, view, field, &device_unchanged);
    expect_same_field(expected, field);
  }
}

TEST_P(PatchMatchStage, PropagateSpatialWithoutConfidence) {
  LevelFixture f(GetParam());
  const SearchSchedule schedule = search_schedule(f.in.ndisp);
  for (int view = 0; view < 2; ++view) {
    for (int parity = 0; parity < 2; ++parity) {
      DeviceField field = upload(f.fields[view], "field");
      propagate_spatial(f.in, view, parity, schedule, nullptr, f.fields[view]);
      stages().propagate_spatial(f.device_in, view, parity, schedule, nullptr, field);
      expect_same_field(f.fields[view], field);
    }
  }
}

// Confident pixels try only the first confident_spatial_candidates candidates; the count
// varies with the case (2 to 12: whole rings and parts of them).
TEST_P(PatchMatchStage, PropagateSpatialWithConfidence) {
  LevelFixture f(GetParam());
  SearchSchedule schedule = search_schedule(f.in.ndisp);
  schedule.confident_spatial_candidates =
      1 + static_cast<int>(GetParam().seed % PMS_SPATIAL_CANDIDATES);
  const std::vector<float> confidence =
      random_confidence(f.fields[0].pixels(), GetParam().seed);
  const Buffer<float> device_confidence = guarded(confidence, "confidence");
  for (int view = 0; view < 2; ++view) {
    for (int parity = 0; parity < 2; ++parity) {
      DeviceField field = upload(f.fields[view], "field");
      propagate_spatial(f.in, view, parity, schedule, &confidence, f.fields[view]);
      stages().propagate_spatial(f.device_in, view, parity, schedule, &device_confidence,
                                 field);
      expect_same_field(f.fields[view], field);
    }
  }
}

TEST_P(PatchMatchStage, PropagateView) {
  LevelFixture f(GetParam());
  advance(f);
  for (int view = 0; view < 2; ++view) {
    for (int parity = 0; parity < 2; ++parity) {
      DeviceField field = upload(f.fields[view], "field");
      const DeviceField other = upload(f.fields[1 - view], "other field");
      propagate_view(f.in, view, parity, SearchSchedule{}, nullptr, f.fields[1 - view],
                     f.fields[view]);
      stages().propagate_view(f.device_in, view, parity, SearchSchedule{}, nullptr, other,
                              field);
      expect_same_field(f.fields[view], field);
      EXPECT_TRUE(same_buffer(f.fields[1 - view].planes, other.planes)) << "input changed";
    }
  }
}

// The finest level's refill iteration: confident pixels keep their planes in every
// stage, the unsure ones search as usual.
TEST_P(PatchMatchStage, UnsurePixelsOnly) {
  LevelFixture f(GetParam());
  advance(f);
  SearchSchedule schedule = search_schedule(f.in.ndisp);
  schedule.unsure_only = true;
  const std::vector<float> confidence =
      random_confidence(f.fields[0].pixels(), GetParam().seed);
  const Buffer<float> device_confidence = guarded(confidence, "confidence");
  for (int view = 0; view < 2; ++view) {
    for (int parity = 0; parity < 2; ++parity) {
      DeviceField field = upload(f.fields[view], "field");
      const DeviceField other = upload(f.fields[1 - view], "other field");
      const PlaneField before = f.fields[view];
      propagate_spatial(f.in, view, parity, schedule, &confidence, f.fields[view]);
      propagate_view(f.in, view, parity, schedule, &confidence, f.fields[1 - view],
                     f.fields[view]);
      refine_random(f.in, view, parity, 9, schedule, &confidence, f.fields[view]);
      for (size_t i = 0; i < confidence.size(); ++i) {
        if (!pms_is_confident(confidence[i], schedule.confident_threshold)) continue;
        ASSERT_EQ(0, std::memcmp(&before.planes[4 * i], &f.fields[view].planes[4 * i],
                                 4 * sizeof(float)))
            << "confident pixel " << i << " changed its plane";
      }
      stages().propagate_spatial(f.device_in, view, parity, schedule, &device_confidence,
                                 field);
      stages().propagate_view(f.device_in, view, parity, schedule, &device_confidence, other,
                              field);
      stages().refine_random(f.device_in, view, parity, 9, schedule, &device_confidence, field);
      expect_same_field(f.fields[view], field);
    }
  }
}

TEST_P(PatchMatchStage, RefineRandomWithoutConfidence) {
  LevelFixture f(GetParam());
  advance(f);
  const SearchSchedule schedule = search_schedule(f.in.ndisp);
  for (int view = 0; view < 2; ++view) {
    for (int parity = 0; parity < 2; ++parity) {
      DeviceField field = upload(f.fields[view], "field");
      refine_random(f.in, view, parity, 5, schedule, nullptr, f.fields[view]);
      stages().refine_random(f.device_in, view, parity, 5, schedule, nullptr, field);
      expect_same_field(f.fields[view], field);
    }
  }
}

TEST_P(PatchMatchStage, RefineRandomWithConfidence) {
  LevelFixture f(GetParam());
  advance(f);
  const SearchSchedule schedule = search_schedule(f.in.ndisp);
  const std::vector<float> confidence =
      random_confidence(f.fields[0].pixels(), GetParam().seed);
  const Buffer<float> device_confidence = guarded(confidence, "confidence");
  for (int view = 0; view < 2; ++view) {
    for (int parity = 0; parity < 2; ++parity) {
      DeviceField field = upload(f.fields[view], "field");
      refine_random(f.in, view, parity, 70, schedule, &confidence, f.fields[view]);
      stages().refine_random(f.device_in, view, parity, 70, schedule, &device_confidence, field);
      expect_same_field(f.fields[view], field);
    }
  }
}

TEST_P(PatchMatchStage, CarryPlanesToFiner) {
  LevelFixture f(GetParam());
  advance(f);
  const PlaneField& coarse = f.fields[0];
  const DeviceField device_coarse = upload(coarse, "coarse");
  // Both finer sizes that halve (rounding up) to the coarse size.
  for (int odd = 0; odd < 2; ++odd) {
    PlaneField fine;
    fine.resize(std::max(1, 2 * coarse.width - odd), std::max(1, 2 * coarse.height - odd));
    carry_planes_to_finer(coarse, fine);
    DeviceField device_fine{fine.width, fine.height,
                            guarded_output<float>(fine.planes.size(), "fine planes"),
                            guarded_output<float>(fine.cost.size(), "fine cost")};
    stages().carry_planes_to_finer(device_coarse, device_fine);
    EXPECT_TRUE(same_buffer(fine.planes, device_fine.planes)) << fine.width << "x" << fine.height;
    read_checked(device_fine.cost, fine.cost.size());  // only the guard matters here
  }
}

TEST_P(PatchMatchStage, PlaneDisparitiesAndConfidence) {
  LevelFixture f(GetParam());
  advance(f);
  const int width = f.fields[0].width;
  const int height = f.fields[0].height;
  std::vector<float> disparity[2];
  Buffer<float> device_disparity[2];
  for (int view = 0; view < 2; ++view) {
    disparity[view] = plane_disparities(f.fields[view], 2);
    device_disparity[view] = guarded_output<float>(disparity[view].size(), "disparity");
    stages().plane_disparities(upload(f.fields[view], "field"), device_disparity[view]);
    EXPECT_TRUE(same_buffer(disparity[view], device_disparity[view]));
  }
  for (int view = 0; view < 2; ++view) {
    const std::vector<float> expected =
        lr_confidence(disparity[view], disparity[1 - view], width, height, view, 2);
    Buffer<float> confidence = guarded_output<float>(expected.size(), "confidence");
    stages().lr_confidence(device_disparity[view], device_disparity[1 - view], width, height,
                           view, confidence);
    EXPECT_TRUE(same_buffer(expected, confidence)) << "view " << view;
  }
}

TEST_P(PatchMatchStage, UpsampleNearest) {
  const LevelCase c = GetParam();
  const std::vector<float> coarse = random_confidence(c.width * c.height, c.seed);
  const Buffer<float> device_coarse = guarded(coarse, "coarse");
  for (int odd = 0; odd < 2; ++odd) {
    const int fine_width = std::max(1, 2 * c.width - odd);
    const int fine_height = std::max(1, 2 * c.height - odd);
    const std::vector<float> expected =
        upsample_nearest(coarse, c.width, c.height, fine_width, fine_height);
    Buffer<float> fine = guarded_output<float>(expected.size(), "fine");
    stages().upsample_nearest(device_coarse, c.width, c.height, fine, fine_width, fine_height);
    EXPECT_TRUE(same_buffer(expected, fine));
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, PatchMatchStage, ::testing::ValuesIn(level_cases()),
                         level_case_name);

// PMS_LANES, the pixels per work item of the cost kernels, is a build option: with 1
// (scalars, for GPUs), 4 or 16 lanes (the tests above run the default, 8) every cost
// stage still gives the reference's bytes, in the order of an iteration.
class CostLanes : public ::testing::TestWithParam<std::tuple<int, LevelCase>> {};

// Stages built with these build options, once per test binary.
OpenClStages& stages_built_with(int lanes, int spatial_group) {
  static std::map<std::pair<int, int>, std::unique_ptr<OpenClStages>> built_with;
  std::unique_ptr<OpenClStages>& built = built_with[{lanes, spatial_group}];
  if (!built) built = std::make_unique<OpenClStages>(context(), nullptr, lanes, spatial_group);
  return *built;
}

TEST_P(CostLanes, EveryCostStageMatchesTheReference) {
  OpenClStages& lanes =
      stages_built_with(std::get<0>(GetParam()), OpenClStages::kDefaultSpatialGroup);
  const LevelCase& c = std::get<1>(GetParam());
  LevelFixture f(c);
  for (int view = 0; view < 2; ++view) {
    DeviceField field = upload(f.fields[view], "field");
    lanes.init_random_planes(f.device_in, view, 0, field);
    expect_same_field(f.fields[view], field);
  }
  advance(f);
  const SearchSchedule schedule = search_schedule(f.in.ndisp);
  const std::vector<float> confidence = random_confidence(f.fields[0].pixels(), c.seed);
  const Buffer<float> device_confidence = guarded(confidence, "confidence");
  for (int view = 0; view < 2; ++view) {
    DeviceField field = upload(f.fields[view], "field");
    const std::vector<std::uint8_t> unchanged = random_consistency(c.width, c.height, c.seed);
    const Buffer<std::uint8_t> device_unchanged = guarded(unchanged, "unchanged");
    std::fill(f.fields[view].cost.begin(), f.fields[view].cost.end(), -1.0f);
    DeviceField partly = upload(f.fields[view], "partly evaluated field");
    PlaneField partly_expected = f.fields[view];
    evaluate_costs(f.in, view, partly_expected, &unchanged);
    lanes.evaluate_costs(f.device_in, view, partly, &device_unchanged);
    expect_same_field(partly_expected, partly);
    evaluate_costs(f.in, view, f.fields[view]);
    lanes.evaluate_costs(f.device_in, view, field);
    expect_same_field(f.fields[view], field);
    for (int parity = 0; parity < 2; ++parity) {
      propagate_spatial(f.in, view, parity, schedule, &confidence, f.fields[view]);
      lanes.propagate_spatial(f.device_in, view, parity, schedule, &device_confidence, field);
      expect_same_field(f.fields[view], field);
      const DeviceField other = upload(f.fields[1 - view], "other field");
      propagate_view(f.in, view, parity, SearchSchedule{}, nullptr, f.fields[1 - view],
                     f.fields[view]);
      lanes.propagate_view(f.device_in, view, parity, SearchSchedule{}, nullptr, other,
                           field);
      expect_same_field(f.fields[view], field);
      refine_random(f.in, view, parity, 9, schedule, &confidence, f.fields[view]);
      lanes.refine_random(f.device_in, view, parity, 9, schedule, &device_confidence, field);
      expect_same_field(f.fields[view], field);
    }
    // The refill iteration's listed launches: the unsure pixels only.
    SearchSchedule unsure_only = schedule;
    unsure_only.unsure_only = true;
    for (int parity = 0; parity < 2; ++parity) {
      propagate_spatial(f.in, view, parity, unsure_only, &confidence, f.fields[view]);
      lanes.propagate_spatial(f.device_in, view, parity, unsure_only, &device_confidence,
                              field);
      const DeviceField other = upload(f.fields[1 - view], "other field");
      propagate_view(f.in, view, parity, unsure_only, &confidence, f.fields[1 - view],
                     f.fields[view]);
      lanes.propagate_view(f.device_in, view, parity, unsure_only, &device_confidence, other,
                           field);
      refine_random(f.in, view, parity, 10, unsure_only, &confidence, f.fields[view]);
      lanes.refine_random(f.device_in, view, parity, 10, unsure_only, &device_confidence,
                          field);
      expect_same_field(f.fields[view], field);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    OneFourAndSixteen, CostLanes,
    ::testing::Combine(::testing::Values(1, 4, 16), ::testing::ValuesIn(level_cases())),
    [](const auto& info) {
      return std::to_string(std::get<0>(info.param)) + "lanes_" +
             case_name(std::get<1>(info.param));
    });

TEST(CostLanesOption, RejectsCountsTheKernelsDoNotHave) {
  EXPECT_THROW(OpenClStages(context(), nullptr, 6), std::invalid_argument);
  EXPECT_THROW(OpenClStages(context(), nullptr, 8, 0), std::invalid_argument);
  EXPECT_THROW(OpenClStages(context(), nullptr, 8, 9), std::invalid_argument);
}

// PMS_SPATIAL_GROUP, the spatial candidates costed in one window pass, is a build option
// too: a group that leaves partial last groups (3) or one candidate at a time (1)
// give the reference's bytes, with every candidate, and with the confident pixels'
// near candidates split at a point that falls inside a group (5) or between (8).
class SpatialGroup : public ::testing::TestWithParam<std::tuple<int, LevelCase>> {};

TEST_P(SpatialGroup, PropagateSpatialMatchesTheReference) {
  OpenClStages& grouped =
      stages_built_with(OpenClStages::kDefaultCostLanes, std::get<0>(GetParam()));
  const LevelCase& c = std::get<1>(GetParam());
  LevelFixture f(c);
  advance(f);
  const std::vector<float> confidence = random_confidence(f.fields[0].pixels(), c.seed);
  const Buffer<float> device_confidence = guarded(confidence, "confidence");
  for (int near : {8, 5}) {
    SearchSchedule schedule = search_schedule(f.in.ndisp);
    schedule.confident_spatial_candidates = near;
    for (int view = 0; view < 2; ++view) {
      DeviceField field = upload(f.fields[view], "field");
      for (int parity = 0; parity < 2; ++parity) {
        const bool with_confidence = parity == 1;
        propagate_spatial(f.in, view, parity, schedule, with_confidence ? &confidence : nullptr,
                          f.fields[view]);
        grouped.propagate_spatial(f.device_in, view, parity, schedule,
                                  with_confidence ? &device_confidence : nullptr, field);
        expect_same_field(f.fields[view], field);
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    OneAndThree, SpatialGroup,
    ::testing::Combine(::testing::Values(1, 3), ::testing::ValuesIn(level_cases())),
    [](const auto& info) {
      return std::to_string(std::get<0>(info.param)) + "group_" +
             case_name(std::get<1>(info.param));
    });

}  // namespace
}  // namespace flexsight::opencl::test

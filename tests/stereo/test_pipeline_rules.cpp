// The schedule rules both schedulers share (host/stereo/pipeline_rules.h): which level does
// what. The byte-exact pipeline tests only prove that the two paths agree; these pin
// the rules themselves.
#include <gtest/gtest.h>

#include "host/stereo/pipeline_rules.h"

using namespace flexsight;

TEST(PlanLevel, OnlyTheCoarsestLevelStartsFromRandomPlanesAndUsesNoConfidence) {
  StereoParams params;
  const int levels = 3;
  for (int level = 0; level < levels; ++level) {
    const LevelPlan plan = plan_level(params, level, levels, 100 >> level, 80 >> level);
    EXPECT_EQ(plan.coarsest, level == levels - 1) << level;
    EXPECT_EQ(plan.use_confidence, level != levels - 1) << level;
    EXPECT_EQ(plan.iterations,
              level == levels - 1 ? params.iterations_coarsest : params.iterations_fine);
    EXPECT_EQ(plan.ndisp, level_ndisp(params.ndisp, level));
  }
}

TEST(PlanLevel, EveryLevelButTheFinestIsCheckedAndFilledBeforeItsPlanesAreCarried) {
  StereoParams params;
  params.fill_coarse = true;
  EXPECT_TRUE(plan_level(params, 2, 3, 25, 20).fill_before_carry);
  EXPECT_TRUE(plan_level(params, 1, 3, 50, 40).fill_before_carry);
  EXPECT_FALSE(plan_level(params, 0, 3, 100, 80).fill_before_carry);  // post-processing does it
  params.fill_coarse = false;
  EXPECT_FALSE(plan_level(params, 2, 3, 25, 20).fill_before_carry);
  EXPECT_FALSE(plan_level(params, 1, 3, 50, 40).fill_before_carry);
}

TEST(PlanLevel, OnlyTheFinestLevelIteratesAgainAfterItsCheckAndFill) {
  StereoParams params;
  params.refill_iterations = 2;
  EXPECT_EQ(plan_level(params, 2, 3, 25, 20).refill_iterations, 0);
  EXPECT_EQ(plan_level(params, 1, 3, 50, 40).refill_iterations, 0);
  const LevelPlan finest = plan_level(params, 0, 3, 100, 80);
  EXPECT_EQ(finest.refill_iterations, 2);
  EXPECT_EQ(finest.refill_label(1), "level 0 (100x80), after the check-and-fill, iteration 1/2");
  params.method = StereoMethod::PMS;  // its only level is the finest
  EXPECT_EQ(plan_level(params, 0, 1, 100, 80).refill_iterations, 2);
  params.refill_iterations = 0;
  EXPECT_EQ(plan_level(params, 0, 3, 100, 80).refill_iterations, 0);
}

// The refill iterations search the pixels that failed the check only, so they need the
// check's confidence even where the level's own iterations run without one (PMS, or
// PPMS's coarsest level were it ever the finest).
TEST(PlanLevel, TheRefillSearchesTheUnsurePixelsOnlyByDefault) {
  StereoParams params;
  const LevelPlan ppms = plan_level(params, 0, 3, 100, 80);
  EXPECT_FALSE(ppms.schedule.unsure_only);
  EXPECT_TRUE(ppms.refill_schedule.unsure_only);
  EXPECT_TRUE(ppms.refill_use_confidence);
  EXPECT_EQ(ppms.refill_schedule.confident_threshold, ppms.schedule.confident_threshold);
  EXPECT_EQ(ppms.refill_schedule.initial_range, ppms.schedule.initial_range);
  params.method = StereoMethod::PMS;
  const LevelPlan pms = plan_level(params, 0, 1, 100, 80);
  EXPECT_FALSE(pms.use_confidence);
  EXPECT_TRUE(pms.refill_use_confidence);
  params.refill_unsure_only = false;  // every pixel, steered as the level's own iterations
  const LevelPlan pms_all = plan_level(params, 0, 1, 100, 80);
  EXPECT_FALSE(pms_all.refill_schedule.unsure_only);
  EXPECT_FALSE(pms_all.refill_use_confidence);
  params.method = StereoMethod::PPMS;
  EXPECT_TRUE(plan_level(params, 0, 3, 100, 80).refill_use_confidence);
}

TEST(PlanLevel, EachMethodTakesItsOwnIterationCounts) {
  StereoParams params;
  params.iterations = 3;
  params.iterations_coarsest = 7;
  params.iterations_fine = 2;
  // PPMS on an image no wider than coarsest_width has one level: it is the coarsest.
  EXPECT_EQ(plan_level(params, 0, 1, 100, 80).iterations, 7);
  EXPECT_EQ(plan_level(params, 1, 2, 50, 40).iterations, 7);
  EXPECT_EQ(plan_level(params, 0, 2, 100, 80).iterations, 2);
  params.method = StereoMethod::PMS;
  EXPECT_EQ(pipeline_level_count(params, 1000, 800), 1);
  EXPECT_EQ(plan_level(params, 0, 1, 1000, 800).iterations, 3);
}

TEST(PlanLevel, BelowTheCoarsestLevelTheSearchStartsAtTheFineRange) {
  StereoParams params;
  params.ndisp = 256;
  EXPECT_EQ(plan_level(params, 2, 3, 25, 20).schedule.initial_range, 32.0f);  // 64 / 2
  EXPECT_EQ(plan_level(params, 1, 3, 50, 40).schedule.initial_range, params.fine_search_range);
  EXPECT_EQ(plan_level(params, 0, 3, 100, 80).name, "level 0 (100x80)");
}

TEST(PlanLevel, EveryLevelTakesTheConfidenceRules) {
  StereoParams params;
  params.confident_threshold = 0.25f;
  params.confident_max_range = 3.0f;
  params.confident_spatial_candidates = 5;
  for (int level = 0; level < 3; ++level) {
    const SearchSchedule schedule = plan_level(params, level, 3, 100 >> level, 80 >> level).schedule;
    EXPECT_EQ(schedule.confident_threshold, 0.25f) << level;
    EXPECT_EQ(schedule.confident_max_range, 3.0f) << level;
    EXPECT_EQ(schedule.confident_spatial_candidates, 5) << level;
  }
}

TEST(PlanLevel, OnlyLevelsThatUseAConfidenceRefreshIt) {
  StereoParams params;
  params.refresh_confidence = true;
  EXPECT_FALSE(plan_level(params, 2, 3, 25, 20).refresh_confidence);  // coarsest: none
  EXPECT_TRUE(plan_level(params, 1, 3, 50, 40).refresh_confidence);
  EXPECT_TRUE(plan_level(params, 0, 3, 100, 80).refresh_confidence);
  params.refresh_confidence = false;
  EXPECT_FALSE(plan_level(params, 0, 3, 100, 80).refresh_confidence);
  params.refresh_confidence = true;
  params.method = StereoMethod::PMS;
  EXPECT_FALSE(plan_level(params, 0, 1, 100, 80).refresh_confidence);
}

TEST(PlanLevel, EveryLevelBelowTheCoarsestTakesTheFineWindowStep) {
  StereoParams params;
  params.window_step = 2;
  params.window_step_fine = 3;
  EXPECT_EQ(plan_level(params, 2, 3, 25, 20).cost.step, 2);  // coarsest: random planes
  EXPECT_EQ(plan_level(params, 1, 3, 50, 40).cost.step, 3);
  EXPECT_EQ(plan_level(params, 0, 3, 100, 80).cost.step, 3);
  EXPECT_EQ(plan_level(params, 0, 1, 100, 80).cost.step, 2);  // a single level is the coarsest
  params.method = StereoMethod::PMS;
  EXPECT_EQ(plan_level(params, 0, 1, 1000, 800).cost.step, 2);
}

TEST(PlanLevel, TheFinestLevelMayTakeItsOwnWindowStepAndIterations) {
  StereoParams params;
  params.window_step = 2;
  params.window_step_fine = 3;
  params.iterations_coarsest = 3;
  params.iterations_fine = 2;
  params.window_step_finest = 5;
  params.iterations_finest = 1;
  EXPECT_EQ(plan_level(params, 2, 3, 25, 20).cost.step, 2);
  EXPECT_EQ(plan_level(params, 2, 3, 25, 20).iterations, 3);
  EXPECT_EQ(plan_level(params, 1, 3, 50, 40).cost.step, 3);
  EXPECT_EQ(plan_level(params, 1, 3, 50, 40).iterations, 2);
  EXPECT_EQ(plan_level(params, 0, 3, 100, 80).cost.step, 5);
  EXPECT_EQ(plan_level(params, 0, 3, 100, 80).iterations, 1);
  // A single level is the coarsest, and PMS has its own counts.
  EXPECT_EQ(plan_level(params, 0, 1, 100, 80).cost.step, 2);
  EXPECT_EQ(plan_level(params, 0, 1, 100, 80).iterations, 3);
  params.method = StereoMethod::PMS;
  EXPECT_EQ(plan_level(params, 0, 1, 1000, 800).cost.step, 2);
  EXPECT_EQ(plan_level(params, 0, 1, 1000, 800).iterations, params.iterations);
  // 0 leaves the finer levels' values.
  params.method = StereoMethod::PPMS;
  params.window_step_finest = 0;
  params.iterations_finest = 0;
  EXPECT_EQ(plan_level(params, 0, 3, 100, 80).cost.step, 3);
  EXPECT_EQ(plan_level(params, 0, 3, 100, 80).iterations, 2);
}

TEST(LevelNdisp, HalvesRoundingUpAndKeepsAtLeastTwo) {
  EXPECT_EQ(level_ndisp(65, 0), 65);
  EXPECT_EQ(level_ndisp(65, 1), 33);
  EXPECT_EQ(level_ndisp(65, 2), 17);
  EXPECT_EQ(level_ndisp(3, 4), 2);
}

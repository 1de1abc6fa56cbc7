// Quality regression on the committed real fixture (Middlebury 2014 Teddy, quarter
// resolution halved again: see datasets.md). Recorded values come from the reference
// path with default parameters; the bound is one-sided so improvements pass and a
// regression of more than one percentage point fails.
#include <gtest/gtest.h>

#include "host/eval/metrics.h"
#include "host/io/image_io.h"
#include "host/io/middlebury_v2.h"
#include "host/io/pfm.h"
#include "host/stereo_pipeline.h"
#include "test_support.h"

using namespace flexsight;

namespace {

SceneScores score_fixture(StereoMethod method, const char* preset = "accurate") {
  const std::string dir = testing_support::fixture_dir();
  StereoPair pair = load_stereo_pair(dir + "/im0.png", dir + "/im1.png");
  StereoParams params;
  if (!apply_stereo_preset(preset, params)) ADD_FAILURE() << "no preset " << preset;
  params.method = method;
  params.ndisp = 32;  // calib.txt of the fixture
  StereoResult result = run_stereo(pair.left, pair.right, params);
  return evaluate_disparity(result.disparity, read_pfm(dir + "/disp0GT.pfm"),
                            read_mask(dir + "/mask0nocc.png"));
}

// Recorded with the default parameters (seed 1), 2026-11-23, with the census term
// (census_weight 4), the post-processing's two weighted medians, the hole median's
// background margin (2 px), PPMS's filling of the coarser levels and its 16-px fine
// search. The margin costs flat PMS on this small crop (4.19 -> 4.63 %) while it gains
// on the 15 full scenes. 2026-11-30: the 2-px limit of the filled disparity's
// extrapolation leaves PPMS here as it was and takes PMS to 4.54 %. Later that day: the
// finest level's window step of 3 costs PPMS on this half-size crop 3.86 -> 4.24 %
// (nonocc 1.74 -> 1.76); on the 15 quarter-resolution scenes it changes nothing
// (12.12 -> 12.11 %) in 0.6x the time. 2026-12-01: the support weight's distance factor
// (gamma_distance 20 px) moves PPMS here 4.24 -> 4.28 % (nonocc 1.76 -> 1.81) and PMS
// 4.54 -> 4.53 %; on the 15 scenes PPMS 12.09 -> 11.93 %. 2026-12-01, later: spatial
// candidates at distances 15 and 45 besides 1 and 5, and PPMS's window step below the
// coarsest level 3 -> 4: PPMS here 4.28 -> 4.19 % (nonocc 1.81 -> 1.88), PMS 4.53 ->
// 4.32 %; on the 15 scenes PPMS 11.93 -> 11.58 %. 2026-12-01, later still: confident
// pixels try only the 8 nearest spatial candidates: PPMS here 4.19 -> 3.81 % (nonocc
// 1.88 -> 1.53), PMS (no confidence) unchanged; on the 15 scenes PPMS 11.58 -> 11.60 %
// in 0.83x the time. Then the confidence refreshed after each finer-level iteration and
// confident pixels' random search limited to 1 px: PPMS here 3.81 -> 3.84 % (nonocc
// 1.53 -> 1.65); on the 15 scenes 11.60 -> 11.44 %. Later: segments under 100 px
// refilled (speckle_size): PPMS here 3.84 -> 3.86 % (nonocc 1.65 -> 1.66), PMS 4.32 ->
// 4.33 % (this half-size crop has few islands that large); on the 15 scenes 11.44 ->
// 11.32 %. Then raw segments under 20 px counted as failing the left/right check
// (raw_speckle_size): PPMS here 3.86 -> 3.71 % (nonocc 1.66 -> 1.52), PMS 4.33 -> 4.40 %;
// on the 15 scenes 11.32 -> 11.14 %. Then one more iteration of the finest level after
// its check-and-fill (refill_iterations): PPMS here 3.71 -> 3.75 % (nonocc 1.52 -> 1.73),
// PMS 4.40 -> 4.27 %; on the 15 scenes 11.14 -> 10.96 % (seed 2: 11.27 -> 11.03).
// 2026-12-02: window rows summed centre first (rounding only): PPMS here 3.75 -> 3.77 %
// (nonocc 1.73 -> 1.74), PMS 4.27 unchanged; on the 15 scenes 10.96 -> 10.92 %. Later:
// only the pixels that fail the check search in that extra iteration
// (refill_unsure_only): PPMS here 3.77 -> 3.78 % (nonocc 1.74 -> 1.60), PMS 4.27 (other
// bytes); on the 15 scenes 10.92 -> 10.95 % in 0.86x the time. Later: the census
// distance capped at 10 bits (census_cap): PPMS here 3.78 -> 3.44 % (nonocc 1.60 ->
// 1.66), PMS 4.27 -> 4.54 %; on the 15 scenes 11.09 -> 10.91 % (mean of seeds 1-5).
// Later: the filled disparity allowed 4 px from its source instead of 2
// (fill_max_extrapolation): PPMS here 3.44 -> 3.49 % (nonocc 1.66), PMS 4.54 -> 4.60 %;
// on the 15 scenes 10.89 -> 10.74 % (mean of seeds 1-3).
constexpr double kRecordedPpmsBad2All = 3.49;
constexpr double kRecordedPpmsBad2Nonocc = 1.66;
constexpr double kRecordedPmsBad2All = 4.60;
// The fast preset (apply_stereo_preset: window steps 3 / 5 / 6, one iteration per finer
// level), recorded 2026-12-02 (4.02 %, nonocc 1.87, with the 2-px fill limit; 4.00 with
// 4 px); on the 15 scenes 11.55 -> 11.45 % (seed 1).
constexpr double kRecordedFastPpmsBad2All = 4.00;
constexpr double kRecordedFastPpmsBad2Nonocc = 1.87;
constexpr double kAllowedRegression = 1.0;  // percentage points

}  // namespace

TEST(QualityRegression, PpmsOnTheTeddyFixture) {
  SceneScores scores = score_fixture(StereoMethod::PPMS);
  std::printf("PPMS fixture: bad-2 all %.2f %%, nonocc %.2f %%\n", scores.all.bad(2.0),
              scores.nonocc.bad(2.0));
  EXPECT_EQ(scores.all.density_percent, 100.0);  // post-processing leaves no hole
  EXPECT_LE(scores.all.bad(2.0), kRecordedPpmsBad2All + kAllowedRegression);
  EXPECT_LE(scores.nonocc.bad(2.0), kRecordedPpmsBad2Nonocc + kAllowedRegression);
}

TEST(QualityRegression, PpmsFastPresetOnTheTeddyFixture) {
  SceneScores scores = score_fixture(StereoMethod::PPMS, "fast");
  std::printf("PPMS fast preset fixture: bad-2 all %.2f %%, nonocc %.2f %%\n",
              scores.all.bad(2.0), scores.nonocc.bad(2.0));
  EXPECT_EQ(scores.all.density_percent, 100.0);
  EXPECT_LE(scores.all.bad(2.0), kRecordedFastPpmsBad2All + kAllowedRegression);
  EXPECT_LE(scores.nonocc.bad(2.0), kRecordedFastPpmsBad2Nonocc + kAllowedRegression);
}

TEST(QualityRegression, PmsOnTheTeddyFixture) {
  SceneScores scores = score_fixture(StereoMethod::PMS);
  std::printf("PMS fixture: bad-2 all %.2f %%\n", scores.all.bad(2.0));
  EXPECT_LE(scores.all.bad(2.0), kRecordedPmsBad2All + kAllowedRegression);
}

// Quality regression on the committed real fixture (Middlebury 2014 Teddy, quarter
// resolution halved again: see datasets.md). Recorded values come from the reference
// path with default parameters; the bound is one-sided so improvements pass and a
// regression of more than one percentage point fails.
#include <gtest/gtest.h>

#include "host/eval/metrics.h"
#include "host/io/image_io.h"
#include "host/io/middlebury_v2.h"
#include "host/io/pfm.h"
#include "host/stereo/stereo_pipeline.h"
#include "tests/common/test_support.h"

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

// Recorded with the default parameters (seed 1) of StereoParams, the reference path.
// This half-size crop does not rank changes as the 15 MiddEval3 Q scenes do (a change
// that gains there can cost a few tenths of a point here, and the other way round), so
// the recorded values follow the defaults chosen on those scenes, and a change of the
// defaults records them again. How they moved with each default is in
// docs/tuning-log.md, "Test fixture history".
constexpr double kRecordedPpmsBad2All = 3.49;
constexpr double kRecordedPpmsBad2Nonocc = 1.66;
constexpr double kRecordedPmsBad2All = 4.60;
// The fast preset (apply_stereo_preset: window steps 3 / 5 / 6, one iteration per finer
// level) on the same defaults; its nonocc value was recorded with a 2-px limit on the
// filled disparity's extrapolation (fill_max_extrapolation), which left bad-2 all within
// 0.02 of the 4-px default's.
constexpr double kRecordedFastPpmsBad2All = 4.00;
constexpr double kRecordedFastPpmsBad2Nonocc = 1.87;
constexpr double kAllowedRegression = 1.0;  // percentage points

}  // namespace

TEST(QualityRegression, PpmsOnTheTeddyFixture) {
  SceneScores scores = score_fixture(StereoMethod::PPMS);
  EXPECT_EQ(scores.all.density_percent, 100.0);  // post-processing leaves no hole
  EXPECT_LE(scores.all.bad(2.0), kRecordedPpmsBad2All + kAllowedRegression)
      << "PPMS bad-2 all " << scores.all.bad(2.0) << " %, recorded " << kRecordedPpmsBad2All;
  EXPECT_LE(scores.nonocc.bad(2.0), kRecordedPpmsBad2Nonocc + kAllowedRegression)
      << "PPMS bad-2 nonocc " << scores.nonocc.bad(2.0) << " %, recorded "
      << kRecordedPpmsBad2Nonocc;
}

TEST(QualityRegression, PpmsFastPresetOnTheTeddyFixture) {
  SceneScores scores = score_fixture(StereoMethod::PPMS, "fast");
  EXPECT_EQ(scores.all.density_percent, 100.0);
  EXPECT_LE(scores.all.bad(2.0), kRecordedFastPpmsBad2All + kAllowedRegression)
      << "fast preset PPMS bad-2 all " << scores.all.bad(2.0) << " %, recorded "
      << kRecordedFastPpmsBad2All;
  EXPECT_LE(scores.nonocc.bad(2.0), kRecordedFastPpmsBad2Nonocc + kAllowedRegression)
      << "fast preset PPMS bad-2 nonocc " << scores.nonocc.bad(2.0) << " %, recorded "
      << kRecordedFastPpmsBad2Nonocc;
}

TEST(QualityRegression, PmsOnTheTeddyFixture) {
  SceneScores scores = score_fixture(StereoMethod::PMS);
  EXPECT_LE(scores.all.bad(2.0), kRecordedPmsBad2All + kAllowedRegression)
      << "PMS bad-2 all " << scores.all.bad(2.0) << " %, recorded " << kRecordedPmsBad2All;
}

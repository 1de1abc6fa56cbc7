// The speed/accuracy presets (apply_stereo_preset), how --preset combines with the
// explicit options on the command line (consume_stereo_params), and the record of every
// parameter that reports carry (stereo_param_values).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "host/stereo/stereo_params.h"
#include "host/cli/arguments.h"
#include "host/io/input_error.h"

using namespace flexsight;

namespace {

// A parameter set whose every non-knob field differs from the defaults, so that a preset
// that touched one of them would show.
StereoParams unusual_params() {
  StereoParams p;
  p.method = StereoMethod::PMS;
  p.ndisp = 77;
  p.window = 31;
  p.window_rows = 13;
  p.alpha = 0.7f;
  p.census_cap = 12.0f;
  p.census_rows = 3;
  p.census_cols = 3;
  p.census_row_length = 19;
  p.gamma = 12.0f;
  p.iterations = 4;
  p.iterations_coarsest = 5;
  p.refill_iterations = 2;
  p.confident_spatial_candidates = 12;
  p.final_median_window = 5;
  p.seed = 9;
  return p;
}

void expect_same_non_knob_fields(const StereoParams& a, const StereoParams& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.ndisp, b.ndisp);
  EXPECT_EQ(a.window, b.window);
  EXPECT_EQ(a.window_rows, b.window_rows);
  EXPECT_EQ(a.alpha, b.alpha);
  EXPECT_EQ(a.census_cap, b.census_cap);
  EXPECT_EQ(a.census_rows, b.census_rows);
  EXPECT_EQ(a.census_cols, b.census_cols);
  EXPECT_EQ(a.census_row_length, b.census_row_length);
  EXPECT_EQ(a.gamma, b.gamma);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_EQ(a.iterations_coarsest, b.iterations_coarsest);
  EXPECT_EQ(a.refill_iterations, b.refill_iterations);
  EXPECT_EQ(a.confident_spatial_candidates, b.confident_spatial_candidates);
  EXPECT_EQ(a.final_median_window, b.final_median_window);
  EXPECT_EQ(a.seed, b.seed);
}

}  // namespace

TEST(StereoPresets, FastSamplesSparserAndIteratesLessBelowTheCoarsestLevel) {
  StereoParams fast = unusual_params();
  ASSERT_TRUE(apply_stereo_preset("fast", fast));
  const StereoParams defaults;
  EXPECT_GT(fast.window_step, defaults.window_step);
  EXPECT_GT(fast.window_step_fine, defaults.window_step_fine);
  EXPECT_GT(fast.window_step_finest, fast.window_step_fine);
  EXPECT_LT(fast.iterations_fine, defaults.iterations_fine);
  EXPECT_GE(fast.iterations_fine, 1);
  EXPECT_GE(fast.iterations_finest, 1);
  expect_same_non_knob_fields(fast, unusual_params());
  // On the defaults the preset makes a valid parameter set with the same knobs, and
  // leaves every other field at its default.
  StereoParams checked;
  ASSERT_TRUE(apply_stereo_preset("fast", checked));
  EXPECT_NO_THROW(checked.check());
  EXPECT_EQ(checked.window_step, fast.window_step);
  EXPECT_EQ(checked.window_step_fine, fast.window_step_fine);
  EXPECT_EQ(checked.window_step_finest, fast.window_step_finest);
  EXPECT_EQ(checked.iterations_fine, fast.iterations_fine);
  EXPECT_EQ(checked.iterations_finest, fast.iterations_finest);
  expect_same_non_knob_fields(checked, defaults);
}

TEST(StereoPresets, AccurateIsTheDefaults) {
  StereoParams p = unusual_params();
  ASSERT_TRUE(apply_stereo_preset("fast", p));
  ASSERT_TRUE(apply_stereo_preset("accurate", p));
  const StereoParams defaults;
  EXPECT_EQ(p.window_step, defaults.window_step);
  EXPECT_EQ(p.window_step_fine, defaults.window_step_fine);
  EXPECT_EQ(p.window_step_finest, defaults.window_step_finest);
  EXPECT_EQ(p.iterations_fine, defaults.iterations_fine);
  EXPECT_EQ(p.iterations_finest, defaults.iterations_finest);
  expect_same_non_knob_fields(p, unusual_params());
}

// The projector-lit bins' preset (docs/stereo.md, "Projector-lit bins"): the accurate
// speed knobs, a 25-px window, the colour and gradient truncations raised above the
// rendered images' true-match residual, an 8-px left/right tolerance, every consistent
// pixel voting in a 5x5 hole median, the texture gate, the flat fill and speckles that
// follow slopes; nothing else moves.
TEST(StereoPresets, ActiveRaisesTheTruncationsAndTheLeftRightTolerance) {
  const StereoParams defaults;
  StereoParams p = unusual_params();
  ASSERT_TRUE(apply_stereo_preset("fast", p));
  ASSERT_TRUE(apply_stereo_preset("active", p));
  EXPECT_EQ(p.window, 25);
  EXPECT_EQ(p.tau_color, 100.0f);
  EXPECT_EQ(p.tau_gradient, 50.0f);
  EXPECT_EQ(p.lr_tolerance, 8.0f);
  EXPECT_TRUE(std::isinf(p.median_background_margin));
  EXPECT_EQ(p.textureless_spread, 4.0f);
  EXPECT_EQ(p.fill_max_extrapolation, 0.0f);
  EXPECT_TRUE(p.speckle_slopes);
  EXPECT_FALSE(defaults.speckle_slopes);
  EXPECT_EQ(p.median_window, 5);
  EXPECT_EQ(p.window_step, defaults.window_step);
  EXPECT_EQ(p.window_step_fine, defaults.window_step_fine);
  EXPECT_EQ(p.window_step_finest, defaults.window_step_finest);
  EXPECT_EQ(p.iterations_fine, defaults.iterations_fine);
  EXPECT_EQ(p.iterations_finest, defaults.iterations_finest);
  StereoParams unusual_with_active_window = unusual_params();
  unusual_with_active_window.window = 25;
  expect_same_non_knob_fields(p, unusual_with_active_window);
  StereoParams checked;
  ASSERT_TRUE(apply_stereo_preset("active", checked));
  EXPECT_NO_THROW(checked.check());
  // The other presets leave those three fields alone.
  for (const char* name : {"accurate", "fast"}) {
    StereoParams q = p;
    ASSERT_TRUE(apply_stereo_preset(name, q));
    EXPECT_EQ(q.tau_color, 100.0f) << name;
    EXPECT_EQ(q.tau_gradient, 50.0f) << name;
    EXPECT_EQ(q.lr_tolerance, 8.0f) << name;
    EXPECT_TRUE(std::isinf(q.median_background_margin)) << name;
  }
  // Through the command line, with an explicit option overriding it.
  std::vector<std::string> args = {"--tau-color", "30", "--preset", "active"};
  StereoParams cli;
  consume_stereo_params(args, cli);
  EXPECT_EQ(cli.tau_color, 30.0f);
  EXPECT_EQ(cli.tau_gradient, 50.0f);
  EXPECT_EQ(cli.lr_tolerance, 8.0f);
  EXPECT_TRUE(std::isinf(cli.median_background_margin));
  EXPECT_TRUE(args.empty());
}

// pick's speed setting on projector-lit pairs: the active preset's cost with the fast
// preset's window steps and iterations.
TEST(StereoPresets, ActiveFastIsTheActiveCostWithTheFastKnobs) {
  StereoParams fast = unusual_params();
  ASSERT_TRUE(apply_stereo_preset("fast", fast));
  StereoParams active = unusual_params();
  ASSERT_TRUE(apply_stereo_preset("active", active));
  StereoParams p = unusual_params();
  ASSERT_TRUE(apply_stereo_preset("active-fast", p));
  EXPECT_EQ(p.window, active.window);
  EXPECT_EQ(p.tau_color, active.tau_color);
  EXPECT_EQ(p.tau_gradient, active.tau_gradient);
  EXPECT_EQ(p.lr_tolerance, active.lr_tolerance);
  EXPECT_TRUE(std::isinf(p.median_background_margin));
  EXPECT_EQ(p.textureless_spread, active.textureless_spread);
  EXPECT_EQ(p.fill_max_extrapolation, active.fill_max_extrapolation);
  EXPECT_EQ(p.speckle_slopes, active.speckle_slopes);
  EXPECT_EQ(p.median_window, active.median_window);
  EXPECT_EQ(p.window_step, fast.window_step);
  EXPECT_EQ(p.window_step_fine, fast.window_step_fine);
  EXPECT_EQ(p.window_step_finest, fast.window_step_finest);
  EXPECT_EQ(p.iterations_fine, fast.iterations_fine);
  EXPECT_EQ(p.iterations_finest, fast.iterations_finest);
  EXPECT_NE(p.window_step, active.window_step) << "the knobs are fast's, not accurate's";
  expect_same_non_knob_fields(p, active);
  StereoParams checked;
  ASSERT_TRUE(apply_stereo_preset("active-fast", checked));
  EXPECT_NO_THROW(checked.check());
}

TEST(StereoPresets, AnUnknownNameChangesNothing) {
  StereoParams p = unusual_params();
  EXPECT_FALSE(apply_stereo_preset("quick", p));
  EXPECT_FALSE(apply_stereo_preset("", p));
  EXPECT_EQ(p.window_step, unusual_params().window_step);
  EXPECT_EQ(p.iterations_fine, unusual_params().iterations_fine);
}

TEST(StereoPresets, ExplicitOptionsOverrideThePresetWhereverItStands) {
  StereoParams fast;
  apply_stereo_preset("fast", fast);
  for (const bool preset_first : {true, false}) {
    std::vector<std::string> preset = {"--preset", "fast"};
    std::vector<std::string> args = {"left.png", "--window-step-finest", "4", "-o", "d.pfm"};
    args.insert(preset_first ? args.begin() : args.end(), preset.begin(), preset.end());
    StereoParams p;
    consume_stereo_params(args, p);
    EXPECT_EQ(p.window_step_finest, 4) << "preset first: " << preset_first;
    EXPECT_EQ(p.window_step_fine, fast.window_step_fine);
    EXPECT_EQ(p.iterations_fine, fast.iterations_fine);
    EXPECT_EQ(args, (std::vector<std::string>{"left.png", "-o", "d.pfm"}));
  }
}

TEST(StereoPresets, TheCommandLineRejectsUnknownAndRepeatedPresets) {
  StereoParams p;
  std::vector<std::string> unknown = {"--preset", "quick"};
  try {
    consume_stereo_params(unknown, p);
    FAIL() << "an unknown preset was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("--preset"), std::string::npos) << message;
    EXPECT_NE(message.find("accurate, fast"), std::string::npos) << message;
  }
  std::vector<std::string> twice = {"--preset", "fast", "--preset", "accurate"};
  EXPECT_THROW(consume_stereo_params(twice, p), InputError);
  std::vector<std::string> missing = {"--preset"};
  EXPECT_THROW(consume_stereo_params(missing, p), InputError);
}

// What a report records reads back as the same parameters: every field, floats to the
// last bit (infinity included), the method and the seed.
TEST(StereoParamValues, ReadBackThroughTheCommandLineAsTheSameParameters) {
  StereoParams original = unusual_params();
  apply_stereo_preset("fast", original);
  original.gamma_distance = INFINITY;
  original.alpha = 0.1f;  // no short decimal: needs every digit
  original.seed = 4000000000u;
  const auto values = stereo_param_values(original);
  std::vector<std::string> args;
  for (const auto& [name, value] : values) {
    EXPECT_EQ(std::count_if(values.begin(), values.end(),
                            [&](const auto& other) { return other.first == name; }),
              1)
        << name;
    args.push_back("--" + name);
    args.push_back(value);
  }
  StereoParams read_back;
  consume_stereo_params(args, read_back);
  EXPECT_TRUE(args.empty());
  EXPECT_EQ(stereo_param_values(read_back), values);
  EXPECT_EQ(read_back.method, StereoMethod::PMS);
  EXPECT_EQ(read_back.seed, 4000000000u);
  EXPECT_EQ(read_back.alpha, 0.1f);
  EXPECT_TRUE(std::isinf(read_back.gamma_distance));
  EXPECT_EQ(read_back.window_step_finest, original.window_step_finest);
  EXPECT_EQ(read_back.census_cap, original.census_cap);
  EXPECT_EQ(read_back.census_row_length, 19);
}

// --census-shape: ROWSxCOLS[+LENGTH] and the two names; shapes the census cannot hold
// (even sides, a centre row shorter than the others, more than 24 bits) are refused by
// name, with the shape as given.
TEST(StereoParamValues, CensusShapeReadsItsFormsAndRefusesImpossibleShapes) {
  const auto shape_of = [](const std::string& text) {
    std::vector<std::string> args = {"--census-shape", text};
    StereoParams p;
    consume_stereo_params(args, p);
    return std::to_string(p.census_rows) + " " + std::to_string(p.census_cols) + " " +
           std::to_string(p.census_row_length);
  };
  EXPECT_EQ(shape_of("row"), "1 25 25");
  EXPECT_EQ(shape_of("square"), "5 5 5");
  EXPECT_EQ(shape_of("3x7"), "3 7 7");
  EXPECT_EQ(shape_of("3x3+19"), "3 3 19");
  for (const std::string bad : {"5", "x5", "5x", "5x5+", "ax5", "-1x5", "5x5x5"}) {
    std::vector<std::string> args = {"--census-shape", bad};
    StereoParams p;
    EXPECT_THROW(consume_stereo_params(args, p), InputError) << bad;
  }
  for (const std::string bad : {"4x5", "5x7", "1x27", "3x3+1", "1x1", "3x5+6"}) {
    std::vector<std::string> args = {"--census-shape", bad};
    StereoParams p;
    consume_stereo_params(args, p);
    try {
      p.check();
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("census-shape"), std::string::npos) << e.what();
    }
  }
}

#include "host/stereo/stereo_params.h"

#include <array>
#include <cmath>
#include <iterator>
#include <string>

#include "host/io/input_error.h"
#include "kernels/stereo/pms_math.h"

namespace flexsight {
namespace {

void require(bool ok, const char* name, const std::string& problem) {
  if (!ok) throw InputError(std::string("parameter --") + name, problem);
}

}  // namespace

void StereoParams::check() const {
  require(ndisp > 0, "ndisp", "must be positive, got " + std::to_string(ndisp));
  require(window >= 1 && window % 2 == 1 && window <= 101, "window",
          "must be odd and in 1..101, got " + std::to_string(window));
  require(window_rows == 0 || (window_rows >= 1 && window_rows % 2 == 1 && window_rows <= 101),
          "window-rows", "must be 0 (= window) or odd and in 1..101, got " +
                             std::to_string(window_rows));
  require(window_step >= 1 && window_step <= window, "window-step",
          "must be in 1..window, got " + std::to_string(window_step));
  require(window_step_fine >= 1 && window_step_fine <= window, "window-step-fine",
          "must be in 1..window, got " + std::to_string(window_step_fine));
  require(std::isfinite(alpha) && alpha >= 0 && alpha <= 1, "alpha", "must be in [0, 1]");
  require(std::isfinite(tau_color) && tau_color > 0, "tau-color", "must be positive");
  require(std::isfinite(tau_gradient) && tau_gradient > 0, "tau-gradient", "must be positive");
  require(std::isfinite(gamma) && gamma > 0, "gamma", "must be positive");
  require(!std::isnan(gamma_distance) && gamma_distance > 0, "gamma-distance",
          "must be positive (inf: colour-only weights)");
  require(std::isfinite(census_weight) && census_weight >= 0, "census-weight", "must be >= 0");
  require(std::isfinite(census_cap) && census_cap >= 0 && census_cap <= 24, "census-cap",
          "must be in [0, 24] (24: no cap)");
  const bool census_odd = census_rows >= 1 && census_rows % 2 == 1 && census_cols >= 1 &&
                          census_cols % 2 == 1 && census_row_length >= census_cols &&
                          census_row_length % 2 == 1;
  const long census_bits = census_odd ? static_cast<long>(census_rows) * census_cols - 1 +
                                            (census_row_length - census_cols)
                                      : 0;
  require(census_odd && census_bits >= 1 && census_bits <= PMS_CENSUS_MAX_BITS,
          "census-shape",
          "needs odd sides, a centre row at least as long as the others and 1..24 bits, got " +
              std::to_string(census_rows) + "x" + std::to_string(census_cols) + "+" +
              std::to_string(census_row_length));
  // At most 50 + 10 iterations per level keep the random generator's iteration keys
  // (iteration_key: 64 per level) distinct.
  require(iterations >= 1 && iterations <= 50, "iterations", "must be in 1..50");
  require(iterations_coarsest >= 1 && iterations_coarsest <= 50, "iterations-coarsest",
          "must be in 1..50");
  require(window_step_finest >= 0 && window_step_finest <= window, "window-step-finest",
          "must be in 0..window (0 = window-step-fine), got " +
              std::to_string(window_step_finest));
  require(iterations_finest >= 0 && iterations_finest <= 50, "iterations-finest",
          "must be in 0..50 (0 = iterations-fine), got " + std::to_string(iterations_finest));
  require(iterations_fine >= 0 && iterations_fine <= 50, "iterations-fine",
          "must be in 0..50");
  require(refill_iterations >= 0 && refill_iterations <= 10, "refill-iterations",
          "must be in 0..10");
  require(std::isfinite(min_search_range) && min_search_range > 0, "min-search-range",
          "must be positive");
  require(std::isfinite(fine_search_range) && fine_search_range > 0, "fine-search-range",
          "must be positive");
  require(std::isfinite(confident_threshold) && confident_threshold >= 0, "confident-threshold",
          "must be >= 0 (above 1 disables the confidence rule)");
  require(std::isfinite(confident_max_range) && confident_max_range >= 0, "confident-max-range",
          "must be >= 0");
  require(confident_spatial_candidates >= 0 &&
              confident_spatial_candidates <= PMS_SPATIAL_CANDIDATES,
          "confident-spatial-candidates",
          "must be in 0.." + std::to_string(PMS_SPATIAL_CANDIDATES) + ", got " +
              std::to_string(confident_spatial_candidates));
  require(std::isfinite(max_normal_delta) && max_normal_delta >= 0 && max_normal_delta <= 2,
          "max-normal-delta", "must be in [0, 2]");
  require(coarsest_width >= 8, "coarsest-width", "must be at least 8");
  require(std::isfinite(lr_tolerance) && lr_tolerance >= 0, "lr-tolerance", "must be >= 0");
  require(!std::isnan(fill_max_extrapolation) && fill_max_extrapolation >= 0,
          "fill-max-extrapolation", "must be >= 0 (inf: no limit)");
  require(median_window >= 1 && median_window % 2 == 1 && median_window <= 101, "median-window",
          "must be odd and in 1..101");
  require(!std::isnan(median_background_margin) && median_background_margin >= 0,
          "median-background-margin", "must be >= 0 (inf: every consistent pixel votes)");
  require(std::isfinite(median_gamma) && median_gamma > 0, "median-gamma", "must be positive");
  require(speckle_size >= 0, "speckle-size", "must be >= 0 (0 = off)");
  require(raw_speckle_size >= 0, "raw-speckle-size", "must be >= 0 (0 = off)");
  require(std::isfinite(textureless_spread) && textureless_spread >= 0, "textureless-spread",
          "must be a finite number >= 0 (0 = off)");
  require(std::isfinite(speckle_range) && speckle_range >= 0, "speckle-range",
          "must be a finite number >= 0");
  require(final_median_window >= 1 && final_median_window % 2 == 1 && final_median_window <= 15,
          "final-median-window", "must be odd and in 1..15 (1 = off)");
  require(std::isfinite(final_median_gamma) && final_median_gamma > 0, "final-median-gamma",
          "must be positive");
  require(threads >= 0 && threads <= 1024, "threads", "must be in 0..1024 (0 = all cores)");
}

const char* method_name(StereoMethod method) {
  return method == StereoMethod::PPMS ? "ppms" : "pms";
}

namespace {

// The speed knobs a preset sets, in the order of its values; the other parameters keep
// theirs.
constexpr int StereoParams::*kSpeedKnobs[] = {
    &StereoParams::window_step,        &StereoParams::window_step_fine,
    &StereoParams::window_step_finest, &StereoParams::iterations_fine,
    &StereoParams::iterations_finest};

using SpeedKnobs = std::array<int, std::size(kSpeedKnobs)>;

// The defaults' knobs.
SpeedKnobs accurate_preset() {
  const StereoParams defaults;
  SpeedKnobs knobs{};
  for (size_t k = 0; k < knobs.size(); ++k) knobs[k] = defaults.*kSpeedKnobs[k];
  return knobs;
}

// Window steps 3 / 5 / 6 (coarsest level / levels between / finest: 144, 49 and 25 of
// the 35x35 window's pixels instead of 324, 81 and 81) and one iteration on every finer
// level (the finest level's refill iteration stays). Of the window-step and iteration
// combinations within the fast mode's time target (docs/tuning-log.md has the targets and
// every combination's figures), the most accurate.
SpeedKnobs fast_preset() { return {3, 5, 6, 1, 1}; }

// Active stereo (a projected dot pattern on dark, texture-less parts; the projector-lit
// bins of docs/stereo.md): the accurate preset's speed knobs, the cost truncations and
// the left/right tolerance below. The figures behind each choice are in
// docs/tuning-log.md ("Preset and stage figures").
// * Truncations. At the true disparity the rendered bins' images differ by more than
//   tau_gradient and tau_color, so the photometric terms are saturated at most of the
//   parts' pixels, barely tell the true match from a wrong one, and the census alone
//   decides. Truncations far above that residual let the dots' contrast count.
// * Left/right tolerance. The bin walls are steep planes that the right view sees
//   compressed, so the right view's disparities there are several pixels off and a 1-px
//   check sends the walls to the background fill.
// * Every consistent pixel votes in the hole median (median_background_margin inf):
//   here most holes are not background but the sides of parts that the right camera does
//   not see and the walls, and the background bound kept their own surface out.
// * Windows without texture fail the check (textureless_spread 4 grey levels), and the
//   fill copies its neighbour's disparity without extrapolating its slope
//   (fill_max_extrapolation 0): beyond the projector's field the table is as plain as a
//   passive image and its raw disparities mostly wrong; the wrong ones that passed the
//   check were the row-wise fill's background, and a slope carried far drifted off.
// * A 25-px support window: the dots are dense enough for it, and a narrower window
//   carries a part's plane less far over the edge onto its neighbour (foreground
//   fattening). Halving the colour bandwidth instead gained the parts as much and cost
//   the walls.
// * Segments that follow slopes (speckle_slopes): the bin walls and the parts' sides are
//   seen at a grazing angle (2 px a row), the 1-px rule cut them into row-sized
//   speckles, and both speckle steps sent them to the floor's disparity.
// * A 5x5 hole median (median_window 5): with every consistent pixel voting, a wide
//   window lets the floor around a wall's or a part side's hole outvote the pixels of the
//   surface itself.
// Not for clean images: on MiddEval3 it is less accurate than the defaults.
struct ActiveCost {
  int window = 25;
  float tau_color = 100.0f;
  float tau_gradient = 50.0f;
  float lr_tolerance = 8.0f;
  float median_background_margin = INFINITY;
  float textureless_spread = 4.0f;
  float fill_max_extrapolation = 0.0f;
  bool speckle_slopes = true;
  int median_window = 5;
};

}  // namespace

bool apply_stereo_preset(const std::string& name, StereoParams& params) {
  SpeedKnobs knobs;
  if (name == "accurate") {
    knobs = accurate_preset();
  } else if (name == "fast") {
    knobs = fast_preset();
  } else if (name == "active" || name == "active-fast") {
    knobs = name == "active" ? accurate_preset() : fast_preset();
    const ActiveCost active;
    params.window = active.window;
    params.tau_color = active.tau_color;
    params.tau_gradient = active.tau_gradient;
    params.lr_tolerance = active.lr_tolerance;
    params.median_background_margin = active.median_background_margin;
    params.textureless_spread = active.textureless_spread;
    params.fill_max_extrapolation = active.fill_max_extrapolation;
    params.speckle_slopes = active.speckle_slopes;
    params.median_window = active.median_window;
  } else {
    return false;
  }
  for (size_t k = 0; k < knobs.size(); ++k) params.*kSpeedKnobs[k] = knobs[k];
  return true;
}

const char* stereo_preset_names() { return "accurate, fast, active, active-fast"; }

}  // namespace flexsight

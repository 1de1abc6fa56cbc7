#include "host/cli/arguments.h"

#include <charconv>
#include <cstring>
#include <functional>
#include <limits>
#include <sstream>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

struct ParamOption {
  const char* name;
  const char* help;
  std::function<void(StereoParams&, const std::string&)> set;
  // The value as the option would take it back (set(get(p)) leaves p as it was).
  std::function<std::string(const StereoParams&)> get;
};

// Shortest text that reads back as the same float ("inf" for infinity).
std::string float_text(float value) {
  char buffer[32];
  const std::to_chars_result end = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, end.ptr);
}

// Integers are read into the field's own type: a value it cannot hold is an error, never
// wrapped around.
template <typename Field>
ParamOption integer_option(const char* name, Field StereoParams::*field, const char* help) {
  return {name, help,
          [name, field](StereoParams& p, const std::string& v) {
            p.*field = static_cast<Field>(parse_whole_number(std::string("--") + name, v,
                                                             std::numeric_limits<Field>::min(),
                                                             std::numeric_limits<Field>::max()));
          },
          [field](const StereoParams& p) { return std::to_string(p.*field); }};
}

// A switch: 1 (on) or 0 (off) on the command line and in reports.
ParamOption flag_option(const char* name, bool StereoParams::*field, const char* help) {
  return {name, help,
          [name, field](StereoParams& p, const std::string& v) {
            if (v != "0" && v != "1") throw InputError(option_subject(name), "must be 0 or 1, got '" + v + "'");
            const int value = v == "1";
            p.*field = value == 1;
          },
          [field](const StereoParams& p) { return std::string(p.*field ? "1" : "0"); }};
}

ParamOption float_option(const char* name, float StereoParams::*field, const char* help,
                         Infinity infinity = Infinity::kRejected) {
  return {name, help,
          [name, field, infinity](StereoParams& p, const std::string& v) { p.*field = parse_float(name, v, infinity); },
          [field](const StereoParams& p) { return float_text(p.*field); }};
}

// --census-shape: ROWSxCOLS, or ROWSxCOLS+LENGTH for a longer centre row; "square" and
// "row" name 5x5 and 1x25. Sizes are checked by StereoParams::check.
ParamOption census_shape_option() {
  return {"census-shape", "census neighbourhood ROWSxCOLS[+CENTRE_ROW_LENGTH] (square = 5x5, row = 1x25)",
          [](StereoParams& p, const std::string& v) {
            const std::string text = v == "square" ? "5x5" : v == "row" ? "1x25" : v;
            const size_t times = text.find('x');
            const size_t plus = text.find('+');
            auto number = [&](size_t begin, size_t end) {
              const std::string part =
                  text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
              if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos) {
                throw InputError(option_subject("census-shape"),
                                 "expected ROWSxCOLS or ROWSxCOLS+LENGTH (e.g. 5x5, 1x25, "
                                 "3x3+19), got '" + v + "'");
              }
              return static_cast<int>(parse_whole_number("--census-shape", part, 1, 101));
            };
            if (times == std::string::npos) number(0, 0);  // empty: the error above
            p.census_rows = number(0, times);
            p.census_cols = number(times + 1, plus);
            p.census_row_length = plus == std::string::npos ? p.census_cols : number(plus + 1, std::string::npos);
          },
          [](const StereoParams& p) {
            std::string text = std::to_string(p.census_rows) + "x" + std::to_string(p.census_cols);
            if (p.census_row_length != p.census_cols) text += "+" + std::to_string(p.census_row_length);
            return text;
          }};
}

// The method, the disparity range and the matching cost.
std::vector<ParamOption> matching_options() {
  return {
      {"method", "ppms (pyramidal, default), pms (flat), or OpenCV's sgbm / bm (peers)",
       [](StereoParams& p, const std::string& v) {
         if (v == "ppms") {
           p.method = StereoMethod::PPMS;
         } else if (v == "pms") {
           p.method = StereoMethod::PMS;
         } else {
           throw InputError(option_subject("method"), "expected ppms, pms, sgbm or bm, got '" + v + "'");
         }
       },
       [](const StereoParams& p) { return std::string(method_name(p.method)); }},
      // One layout for every row: the option and the field it sets, then its help.
      // clang-format off
      integer_option("ndisp", &StereoParams::ndisp,
                     "disparity range [0, ndisp - 1]"),
      integer_option("window", &StereoParams::window,
                     "support window side (odd)"),
      integer_option("window-rows", &StereoParams::window_rows,
                     "support window rows (odd, 0 = window)"),
      integer_option("window-step", &StereoParams::window_step,
                     "sample every n-th window row/column"),
      integer_option("window-step-fine", &StereoParams::window_step_fine,
                     "PPMS: window step below the coarsest level"),
      integer_option("window-step-finest", &StereoParams::window_step_finest,
                     "PPMS: window step on the finest level (0 = window-step-fine)"),
      float_option("alpha", &StereoParams::alpha,
                   "weight of the gradient term"),
      float_option("tau-color", &StereoParams::tau_color,
                   "colour truncation"),
      float_option("tau-gradient", &StereoParams::tau_gradient,
                   "gradient truncation"),
      float_option("gamma", &StereoParams::gamma,
                   "support weight bandwidth"),
      float_option("gamma-distance", &StereoParams::gamma_distance,
                   "support weight distance bandwidth (px, inf = off)", Infinity::kMeaningful),
      float_option("census-weight", &StereoParams::census_weight,
                   "weight of the census distance (0 = off)"),
      float_option("census-cap", &StereoParams::census_cap,
                   "census distance counted up to this many bits (24 = no cap)"),
      census_shape_option(),
      // clang-format on
  };
}

// The PatchMatch iterations and their random search.
std::vector<ParamOption> search_options() {
  return {
      // clang-format off
      integer_option("iterations", &StereoParams::iterations,
                     "PMS: iterations on its only level"),
      integer_option("iterations-coarsest", &StereoParams::iterations_coarsest,
                     "PPMS: iterations on the coarsest level"),
      integer_option("iterations-fine", &StereoParams::iterations_fine,
                     "PPMS: iterations on the finer levels"),
      integer_option("iterations-finest", &StereoParams::iterations_finest,
                     "PPMS: iterations on the finest level (0 = iterations-fine)"),
      float_option("min-search-range", &StereoParams::min_search_range,
                   "smallest random-search range (px)"),
      float_option("fine-search-range", &StereoParams::fine_search_range,
                   "PPMS: first random-search range below the coarsest level (px)"),
      float_option("confident-threshold", &StereoParams::confident_threshold,
                   "confidence from which search is reduced"),
      float_option("confident-max-range", &StereoParams::confident_max_range,
                   "largest search range for confident pixels (px)"),
      integer_option("confident-spatial-candidates", &StereoParams::confident_spatial_candidates,
                     "PPMS: spatial candidates a confident pixel tries (0..16, nearest first)"),
      flag_option("refresh-confidence", &StereoParams::refresh_confidence,
                     "PPMS: recompute the confidence after each finer-level iteration (0/1)"),
      float_option("max-normal-delta", &StereoParams::max_normal_delta,
                   "normal perturbation of the first trial"),
      integer_option("coarsest-width", &StereoParams::coarsest_width,
                     "PPMS: widest allowed coarsest level"),
      // clang-format on
  };
}

// The left/right check, the filling of what it rejects, the medians and the speckle filters.
std::vector<ParamOption> filling_options() {
  return {
      // clang-format off
      integer_option("refill-iterations", &StereoParams::refill_iterations,
                     "iterations after the finest level's check-and-fill (0 = none)"),
      flag_option("refill-unsure-only", &StereoParams::refill_unsure_only,
                     "only the pixels that fail the check search in those iterations (0/1)"),
      flag_option("fill-coarse", &StereoParams::fill_coarse,
                     "PPMS: fill occlusions before carrying planes (0/1)"),
      float_option("lr-tolerance", &StereoParams::lr_tolerance,
                   "left/right check tolerance (px)"),
      integer_option("median-window", &StereoParams::median_window,
                     "weighted median window (odd)"),
      float_option("median-gamma", &StereoParams::median_gamma,
                   "weighted median colour bandwidth"),
      float_option("fill-max-extrapolation", &StereoParams::fill_max_extrapolation,
                   "filled disparity at most this far from its source pixel's (px, inf = plane)",
                   Infinity::kMeaningful),
      float_option("median-background-margin", &StereoParams::median_background_margin,
                   "hole median: votes at most this far above the filled disparity (px)"),
      integer_option("final-median-window", &StereoParams::final_median_window,
                     "weighted median over all pixels (odd, 1 = off)"),
      float_option("final-median-gamma", &StereoParams::final_median_gamma,
                   "its colour bandwidth"),
      integer_option("speckle-size", &StereoParams::speckle_size,
                     "refill segments smaller than this (px, 0 = off)"),
      float_option("speckle-range", &StereoParams::speckle_range,
                   "their neighbours' largest disparity step (px)"),
      flag_option("speckle-slopes", &StereoParams::speckle_slopes,
                  "segments also join a step that continues the next one (0/1)"),
      integer_option("raw-speckle-size", &StereoParams::raw_speckle_size,
                     "raw segments smaller than this fail the left/right check (px, 0 = off)"),
      float_option("textureless-spread", &StereoParams::textureless_spread,
                   "windows with a grey spread below this fail the check (0 = off)"),
      // clang-format on
  };
}

// How a run goes: its seed and threads.
std::vector<ParamOption> run_options() {
  return {
      {"seed", "random generator seed",
       [](StereoParams& p, const std::string& v) {
         p.seed = static_cast<std::uint32_t>(parse_whole_number("--seed", v, 0, 0xffffffffLL));
       },
       [](const StereoParams& p) { return std::to_string(p.seed); }},
      integer_option("threads", &StereoParams::threads,
                     "reference-path threads (0 = all cores)"),
  };
}

const std::vector<ParamOption>& param_options() {
  static const std::vector<ParamOption> options = [] {
    std::vector<ParamOption> all;
    for (const std::vector<ParamOption>& group :
         {matching_options(), search_options(), filling_options(), run_options()}) {
      all.insert(all.end(), group.begin(), group.end());
    }
    return all;
  }();
  return options;
}

}  // namespace

void consume_stereo_params(std::vector<std::string>& args, StereoParams& params) {
  // The preset first, wherever it stands, so that explicit options override it.
  const std::string preset = take_option(args, "--preset");
  if (!preset.empty()) {
    if (!take_option(args, "--preset").empty()) throw InputError("option --preset", "given twice");
    if (!apply_stereo_preset(preset, params)) {
      throw InputError("option --preset", std::string("expected one of ") +
                                               stereo_preset_names() + ", got '" + preset + "'");
    }
  }
  std::vector<std::string> rest;
  for (size_t i = 0; i < args.size(); ++i) {
    const ParamOption* match = nullptr;
    for (const ParamOption& option : param_options()) {
      if (args[i] == std::string("--") + option.name) match = &option;
    }
    if (!match) {
      rest.push_back(args[i]);
      continue;
    }
    if (i + 1 >= args.size()) throw InputError(option_subject(match->name), "needs a value");
    match->set(params, args[++i]);
  }
  args = rest;
}

std::vector<std::pair<std::string, std::string>> stereo_param_values(const StereoParams& params) {
  std::vector<std::pair<std::string, std::string>> values;
  for (const ParamOption& option : param_options()) values.emplace_back(option.name, option.get(params));
  return values;
}

std::string stereo_params_help() {
  std::ostringstream out;
  out << "  --preset NAME                 speed/accuracy settings: accurate (default) or fast\n"
         "                                (window steps and iterations), or active for\n"
         "                                projector-lit scenes (accurate, with a 25-px\n"
         "                                window, higher cost truncations, an 8-px\n"
         "                                left/right tolerance, a 5x5 hole median without\n"
         "                                background bound, plain windows failing the check, a\n"
         "                                flat fill and speckles that follow slopes), or\n"
         "                                active-fast (active's cost, fast's steps); the\n"
         "                                options below override it\n";
  for (const ParamOption& option : param_options()) {
    out << "  --" << option.name << " VALUE";
    // A name too long for the column gets its help on the next line, as --device's does.
    constexpr size_t kNameColumn = 22;
    const size_t name_width = std::string(option.name).size();
    if (name_width >= kNameColumn) {
      out << "\n" << std::string(std::strlen("  --") + kNameColumn + std::strlen(" VALUE"), ' ');
    } else {
      out << std::string(kNameColumn - name_width, ' ');
    }
    out << option.help << "\n";
  }
  return out.str();
}

}  // namespace flexsight

#pragma once
// Command-line parsing shared by the subcommands.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <optional>

#include "host/stereo/stereo_params.h"
#include "host/stereo/opencv_stereo.h"

namespace flexsight {

// Walks `args`; for each "--name value" naming a StereoParams field (kebab-case, e.g.
// --window-step, --tau-color, --method, --seed, --threads, --ndisp) sets that field and
// removes both tokens. Leaves all other tokens in place, in order. Throws InputError
// ("option --x: ...") for a missing or malformed value.
void consume_stereo_params(std::vector<std::string>& args, StereoParams& params);

// --method sgbm|bm picks an OpenCV peer matcher: removes the option and returns it.
// --method ppms|pms (or none) stays in `args` for consume_stereo_params.
std::optional<OpenCvMatcher> take_opencv_method(std::vector<std::string>& args);

// Removes "--name value" from args and returns value, or "" if absent.
std::string take_option(std::vector<std::string>& args, const std::string& name);

// take_option for each (name, destination) in turn: a command's plain string options as
// one table.
void take_options(std::vector<std::string>& args,
                  const std::vector<std::pair<std::string, std::string*>>& options);

// Removes "--name value" from args and returns value as a number, or `fallback` if
// absent. Throws InputError ("option --name: expected a number ...") when malformed.
double take_number_option(std::vector<std::string>& args, const std::string& name,
                          double fallback);

// `text`, the value of `option` ("--count"), as a whole number in lo..hi. Throws
// InputError ("option --count: expected a whole number in 1..100, got '4294967312'") for
// anything else: no wrap-around into the range, no trailing characters, no fraction.
std::int64_t parse_whole_number(const std::string& option, const std::string& text,
                                std::int64_t lo, std::int64_t hi);

// "option --name": the subject of an option's InputError.
std::string option_subject(const std::string& name);

// Whether a float option may be infinite: only where infinity has a documented meaning
// ("inf = off"); NaN never is a value.
enum class Infinity { kRejected, kMeaningful };

// The value of option `name` (without dashes) read from the whole of `text`; InputError
// naming the option for anything else, and for an infinity `infinity` rejects.
float parse_float(const std::string& name, const std::string& text, Infinity infinity = Infinity::kRejected);

// Removes "--name" from args and returns whether it was there.
bool take_flag(std::vector<std::string>& args, const std::string& name);

// A command's exit code when it only prints its usage: 0 for --help or -h (taken out of
// `args`), 1 for no arguments at all (a usage error); nullopt when the command runs.
std::optional<int> usage_exit_code(std::vector<std::string>& args, void (*print_help)());

// Throws InputError ("option --x: unknown option") if any token starts with "--".
void reject_unknown_options(const std::vector<std::string>& args);

// Every StereoParams option as (name without dashes, value), in --help's order; each
// value reads back through consume_stereo_params as the same field value. For the
// record of a run (flexsight eval's reports).
std::vector<std::pair<std::string, std::string>> stereo_param_values(const StereoParams& params);

// One line per StereoParams option, for --help.
std::string stereo_params_help();

}  // namespace flexsight

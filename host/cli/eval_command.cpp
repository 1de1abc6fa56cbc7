// flexsight eval: scores the matcher (or results computed elsewhere) on a benchmark
// folder and writes pictures plus a Markdown and a JSON report.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "host/cli/arguments.h"
#include "host/cli/backend.h"
#include "host/cli/commands.h"
#include "host/eval/dataset.h"
#include "host/eval/report.h"
#include "host/eval/stereo_evaluation.h"
#include "host/io/atomic_file.h"
#include "host/io/input_error.h"

namespace flexsight {

namespace {

namespace fs = std::filesystem;

struct EvalOptions {
  std::string dataset_root;
  std::vector<std::string> scene_names;  // empty = every scene
  StereoEvalOptions run;                 // --method sgbm|bm: run.opencv, an OpenCV peer
  BackendOptions backend;
};

void print_help() {
  std::cout << "usage: flexsight eval DATASET_ROOT [options] [stereo params]\n"
               "  DATASET_ROOT           MiddEval3, Middlebury v2 or KITTI training folder, or one scene\n"
               "  --results DIR          score DIR/<scene>.pfm, DIR/<scene>/disp0*.pfm or\n"
               "                         DIR/<scene>_disp.pfm (an earlier --out) instead of running\n"
               "                         the matcher\n"
               "  --out DIR              output folder (default eval_out)\n"
               "  --scenes A,B,C         only these scenes\n"
               "  --repeat N             match each scene N times and report the median time\n"
               "                         (the results are identical: the matcher is deterministic)\n"
               "  --max-disp-color N     disparity shown as the top colour (default: the scene's ndisp)\n"
               "The disparity range (ndisp) comes from each scene; --ndisp is rejected.\n"
            << backend_options_help() << "Stereo params:\n"
            << stereo_params_help();
}

// The names of --scenes: comma-separated, spaces around them ignored. An empty list or
// an empty name ("A,,B", "A,") is an error: a selection that names nothing must not
// widen to every scene.
std::vector<std::string> split_scene_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    const auto first = item.find_first_not_of(" \t");
    const auto last = item.find_last_not_of(" \t");
    if (first == std::string::npos) {
      throw InputError("option --scenes", "has an empty scene name in '" + text + "' (expected A,B,C)");
    }
    items.push_back(item.substr(first, last - first + 1));
  }
  if (items.empty() || text.back() == ',') {
    throw InputError("option --scenes", "names no scene in '" + text + "' (expected A,B,C)");
  }
  return items;
}

float parse_positive(const std::string& option, const std::string& text) {
  try {
    std::size_t used = 0;
    const float value = std::stof(text, &used);
    if (used == text.size() && std::isfinite(value) && value > 0) return value;
  } catch (const std::exception&) {
    // reported below, with the option's name
  }
  throw InputError("option " + option, "expected a positive number, got '" + text + "'");
}

// Every PatchMatch parameter of the run but ndisp, which each scene sets for itself.
std::vector<ReportParameter> report_parameters(const StereoParams& params) {
  const auto defaults = stereo_param_values(StereoParams{});
  std::vector<ReportParameter> parameters;
  for (const auto& [name, value] : stereo_param_values(params)) {
    if (name == "ndisp") continue;
    bool is_default = false;
    for (const auto& [default_name, default_value] : defaults) {
      if (default_name == name) is_default = default_value == value;
    }
    parameters.push_back({name, value, is_default});
  }
  return parameters;
}

EvalOptions parse_options(std::vector<std::string> args) {
  EvalOptions options;
  // Each scene brings its own disparity range; a global one would silently cut
  // scenes short or waste time, so it is an error rather than ignored.
  if (std::find(args.begin(), args.end(), "--ndisp") != args.end()) {
    throw InputError("option --ndisp", "eval takes ndisp from each scene; remove the option");
  }
  options.run.opencv = take_opencv_method(args);
  consume_stereo_params(args, options.run.params);
  options.backend = take_backend_options(args);
  options.run.results_dir = take_option(args, "--results");
  const std::string out = take_option(args, "--out");
  if (!out.empty()) options.run.out_dir = out;
  const bool scenes_given = std::find(args.begin(), args.end(), "--scenes") != args.end();
  const std::string scenes = take_option(args, "--scenes");
  if (scenes_given) options.scene_names = split_scene_list(scenes);
  const std::string repeat = take_option(args, "--repeat");
  if (!repeat.empty()) {
    const float runs = parse_positive("--repeat", repeat);
    if (runs != static_cast<int>(runs) || runs > 100) {
      throw InputError("option --repeat", "expected a whole number from 1 to 100, got '" + repeat + "'");
    }
    options.run.repeat = static_cast<int>(runs);
  }
  const std::string max_disp = take_option(args, "--max-disp-color");
  if (!max_disp.empty()) options.run.max_disp_color = parse_positive("--max-disp-color", max_disp);
  reject_unknown_options(args);
  if (args.size() != 1) {
    throw InputError("DATASET_ROOT", args.empty() ? "missing (see flexsight eval --help)"
                                                  : "expected one folder, got " +
                                                        std::to_string(args.size()) + " arguments");
  }
  options.dataset_root = args.front();
  options.run.parameters = report_parameters(options.run.params);
  return options;
}

// Keeps the scenes named by --scenes, in dataset order; an unknown name is an error so
// a typo never shrinks a benchmark silently.
std::vector<Scene> select_scenes(std::vector<Scene> scenes, const std::vector<std::string>& names) {
  if (names.empty()) return scenes;
  std::set<std::string> known;
  for (const Scene& scene : scenes) known.insert(scene.name);
  for (const std::string& name : names) {
    if (known.count(name) == 0) {
      std::string available;
      for (const std::string& k : known) available += (available.empty() ? "" : ", ") + k;
      throw InputError("option --scenes", "unknown scene '" + name + "' (available: " + available + ")");
    }
  }
  const std::set<std::string> wanted(names.begin(), names.end());
  scenes.erase(std::remove_if(scenes.begin(), scenes.end(),
                              [&](const Scene& scene) { return wanted.count(scene.name) == 0; }),
               scenes.end());
  return scenes;
}

void write_text(const std::string& path, const std::string& text) {
  write_atomically(path, [&text](const std::string& tmp_path) {
    std::ofstream file(tmp_path, std::ios::binary);
    file << text;
    file.close();
    if (!file) throw InputError(tmp_path, "cannot write file");
  });
}

void make_output_dir(const std::string& dir) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error || !fs::is_directory(dir)) {
    throw InputError(dir, "cannot create output folder" + (error ? ": " + error.message() : ""));
  }
}

}  // namespace

int run_eval_command(std::vector<std::string> args) {
  if (std::find(args.begin(), args.end(), "--help") != args.end() ||
      std::find(args.begin(), args.end(), "-h") != args.end()) {
    print_help();
    return 0;
  }
  const EvalOptions options = parse_options(std::move(args));
  const std::vector<Scene> scenes =
      select_scenes(discover_scenes(options.dataset_root), options.scene_names);
  check_scenes_before_running(scenes, options.run);
  make_output_dir(options.run.out_dir);
  const EvalReport report = evaluate_stereo_scenes(options.dataset_root, scenes, options.run, options.backend);
  const std::string markdown = to_markdown(report);
  write_text((fs::path(options.run.out_dir) / "report.md").string(), markdown);
  write_text((fs::path(options.run.out_dir) / "report.json").string(), to_json(report));
  std::cout << markdown;
  return 0;
}

}  // namespace flexsight

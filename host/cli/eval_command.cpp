// flexsight eval: scores the matcher (or results computed elsewhere) on a benchmark
// folder and writes pictures plus a Markdown and a JSON report.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "host/cli/arguments.h"
#include "host/cli/backend.h"
#include "host/cli/commands.h"
#include "host/eval/colorize.h"
#include "host/eval/dataset.h"
#include "host/eval/metrics.h"
#include "host/eval/report.h"
#include "host/stereo/confidence_map.h"
#include "host/geometry/stereo_camera.h"
#include "host/io/atomic_file.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/pfm.h"
#include "host/stereo/stereo_pipeline.h"

namespace flexsight {

namespace {

namespace fs = std::filesystem;

constexpr float kErrorMapThreshold = 2.0f;

const char* const kConventions =
    "Errors at the ground truth's resolution; 'all' = every pixel with ground truth, "
    "'nonocc' = mask 255; pixels without a result count as bad; average = unweighted mean "
    "over scenes.";

struct EvalOptions {
  std::string dataset_root;
  std::string results_dir;  // "" = run the matcher
  std::string out_dir = "eval_out";
  std::vector<std::string> scene_names;  // empty = every scene
  float max_disp_color = 0;              // 0 = each scene's ndisp
  StereoParams params;
  std::optional<OpenCvMatcher> opencv;  // --method sgbm|bm: an OpenCV peer instead
  int repeat = 1;                        // runs per scene; the median time is reported
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

EvalOptions parse_options(std::vector<std::string> args) {
  EvalOptions options;
  // Each scene brings its own disparity range; a global one would silently cut
  // scenes short or waste time, so it is an error rather than ignored.
  if (std::find(args.begin(), args.end(), "--ndisp") != args.end()) {
    throw InputError("option --ndisp", "eval takes ndisp from each scene; remove the option");
  }
  options.opencv = take_opencv_method(args);
  consume_stereo_params(args, options.params);
  options.backend = take_backend_options(args);
  options.results_dir = take_option(args, "--results");
  const std::string out = take_option(args, "--out");
  if (!out.empty()) options.out_dir = out;
  const bool scenes_given = std::find(args.begin(), args.end(), "--scenes") != args.end();
  const std::string scenes = take_option(args, "--scenes");
  if (scenes_given) options.scene_names = split_scene_list(scenes);
  const std::string repeat = take_option(args, "--repeat");
  if (!repeat.empty()) {
    const float runs = parse_positive("--repeat", repeat);
    if (runs != static_cast<int>(runs) || runs > 100) {
      throw InputError("option --repeat", "expected a whole number from 1 to 100, got '" + repeat + "'");
    }
    options.repeat = static_cast<int>(runs);
  }
  const std::string max_disp = take_option(args, "--max-disp-color");
  if (!max_disp.empty()) options.max_disp_color = parse_positive("--max-disp-color", max_disp);
  reject_unknown_options(args);
  if (args.size() != 1) {
    throw InputError("DATASET_ROOT", args.empty() ? "missing (see flexsight eval --help)"
                                                  : "expected one folder, got " +
                                                        std::to_string(args.size()) + " arguments");
  }
  options.dataset_root = args.front();
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

// Result files named after the scene (DIR/<scene>.pfm), laid out as a MiddEval3
// submission folder (DIR/<Scene>/disp0<METHOD>.pfm, disp0.pfm preferred), or left by an
// earlier eval run (DIR/<scene>_disp.pfm), so an --out folder can be re-scored.
std::string find_result_file(const std::string& results_dir, const std::string& scene_name) {
  const fs::path dir(results_dir);
  std::vector<fs::path> candidates = {dir / (scene_name + ".pfm"), dir / scene_name / "disp0.pfm",
                                      dir / (scene_name + "_disp.pfm")};
  std::error_code error;
  std::vector<fs::path> others;
  for (fs::directory_iterator it(dir / scene_name, error), end; !error && it != end;
       it.increment(error)) {
    const std::string file = it->path().filename().string();
    if (file.rfind("disp0", 0) == 0 && it->path().extension() == ".pfm") others.push_back(it->path());
  }
  std::sort(others.begin(), others.end());
  candidates.insert(candidates.end(), others.begin(), others.end());
  for (const fs::path& candidate : candidates) {
    if (fs::is_regular_file(candidate, error)) return candidate.string();
  }
  throw InputError(candidates.front().string(),
                   "result file not found (also looked for " +
                       (dir / scene_name / "disp0*.pfm").string() + " and " +
                       candidates[2].string() + ")");
}

cv::Mat read_result(const std::string& path, const cv::Mat& ground_truth) {
  cv::Mat disparity = read_pfm(path);
  if (disparity.type() != CV_32FC1) throw InputError(path, "expected a one-channel PFM (Pf)");
  if (disparity.size() != ground_truth.size()) {
    throw InputError(path, "is " + std::to_string(disparity.cols) + "x" +
                               std::to_string(disparity.rows) + " but the ground truth is " +
                               std::to_string(ground_truth.cols) + "x" +
                               std::to_string(ground_truth.rows) +
                               " (errors are measured at the ground truth's resolution)");
  }
  return disparity;
}

// The confidence map beside a result file: X_disp.pfm -> X_conf.pfm (what an earlier
// eval run wrote). Empty when there is none.
cv::Mat read_companion_confidence(const std::string& result_path, const cv::Mat& ground_truth) {
  std::string path = result_path;
  const std::string suffix = "_disp.pfm";
  if (path.size() < suffix.size() || path.compare(path.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return {};
  }
  path.replace(path.size() - suffix.size(), suffix.size(), "_conf.pfm");
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return {};
  return read_result(path, ground_truth);
}

struct MatchOutcome {
  cv::Mat disparity;
  cv::Mat confidence;  // empty when results come from files without a _conf.pfm
  double seconds = 0;
  std::string matcher;  // the path that ran (a device can fall back to the reference)
};

MatchOutcome run_opencv(OpenCvMatcher matcher, const Scene& scene, const std::string& tag) {
  const StereoPair pair = load_stereo_pair(scene.left_path, scene.right_path);
  std::cerr << tag << ": " << opencv_matcher_name(matcher) << "\n";
  const auto start = std::chrono::steady_clock::now();
  MatchOutcome outcome;
  outcome.disparity = run_opencv_matcher(matcher, pair.left, pair.right, scene.ndisp);
  outcome.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.3f s", outcome.seconds);
  std::cerr << tag << ": " << seconds << "\n";
  return outcome;
}

MatchOutcome run_matcher(StereoBackend& backend, const Scene& scene, StereoParams params,
                         const std::string& tag) {
  const StereoPair pair = load_stereo_pair(scene.left_path, scene.right_path);
  params.ndisp = scene.ndisp;
  const auto progress = [&tag](const std::string& stage) {
    std::cerr << tag << ": " << stage << "\n";
  };
  const auto start = std::chrono::steady_clock::now();
  std::string used;
  StereoResult result = backend.run(pair.left, pair.right, params, progress, &used);
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.3f s", elapsed.count());
  std::cerr << tag << ": " << seconds << " on the " << used << "\n";
  return {result.disparity, confidence_map(result, pair.left, params), elapsed.count(), used};
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

// Everything that can be checked cheaply is checked before the first scene is matched,
// so a missing file does not surface only after minutes of matching.
void check_scenes_before_running(const std::vector<Scene>& scenes, const EvalOptions& options) {
  for (const Scene& scene : scenes) {
    if (scene.gt_path.empty()) throw InputError(scene.left_path, "scene has no ground truth");
    if (!options.results_dir.empty()) find_result_file(options.results_dir, scene.name);
  }
}

// `backend`: null when the results are read from files.
SceneReport evaluate_scene(StereoBackend* backend, const Scene& scene, const EvalOptions& options,
                           const std::string& tag) {
  // Ground truth first: a broken dataset fails before minutes of matching.
  const GroundTruth truth = load_ground_truth(scene);
  const std::string out = (fs::path(options.out_dir) / scene.name).string();

  MatchOutcome outcome;
  if (options.results_dir.empty()) {
    std::vector<double> seconds;
    for (int run = 0; run < options.repeat; ++run) {
      const std::string run_tag =
          options.repeat > 1 ? tag + " (run " + std::to_string(run + 1) + "/" +
                                   std::to_string(options.repeat) + ")"
                             : tag;
      outcome = options.opencv ? run_opencv(*options.opencv, scene, run_tag)
                               : run_matcher(*backend, scene, options.params, run_tag);
      seconds.push_back(outcome.seconds);
    }
    std::sort(seconds.begin(), seconds.end());
    const size_t mid = seconds.size() / 2;
    outcome.seconds = seconds.size() % 2 ? seconds[mid] : 0.5 * (seconds[mid - 1] + seconds[mid]);
    if (outcome.disparity.size() != truth.disparity.size()) {
      throw InputError(scene.gt_path, "ground truth differs in size from the images");
    }
    write_pfm(out + "_disp.pfm", outcome.disparity);
    if (!outcome.confidence.empty()) write_pfm(out + "_conf.pfm", outcome.confidence);
  } else {
    const std::string path = find_result_file(options.results_dir, scene.name);
    std::cerr << tag << ": reading " << path << "\n";
    outcome.disparity = read_result(path, truth.disparity);
    outcome.confidence = read_companion_confidence(path, truth.disparity);
  }

  SceneReport report;
  report.name = scene.name;
  report.width = truth.disparity.cols;
  report.height = truth.disparity.rows;
  report.ndisp = scene.ndisp;
  report.seconds = outcome.seconds;
  report.matcher = outcome.matcher;
  report.scores = evaluate_disparity(outcome.disparity, truth.disparity, truth.nonocc);
  report.confident = evaluate_confident(outcome.disparity, truth.disparity, outcome.confidence);
  if (!scene.calib_path.empty()) {
    const StereoCamera camera = read_stereo_camera(scene.calib_path)
                                    .resized_to(truth.disparity.cols, truth.disparity.rows);
    report.depth = evaluate_depth(outcome.disparity, truth.disparity, outcome.confidence, camera);
  }

  const float max_disp = options.max_disp_color > 0 ? options.max_disp_color
                                                    : static_cast<float>(scene.ndisp);
  write_image(out + "_disp.png", colorize_disparity(outcome.disparity, max_disp));
  write_image(out + "_error.png",
              error_map(outcome.disparity, truth.disparity, truth.nonocc, kErrorMapThreshold));
  return report;
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
  check_scenes_before_running(scenes, options);
  make_output_dir(options.out_dir);
  // The device is chosen and the kernels are built once, for every scene.
  std::unique_ptr<StereoBackend> backend;
  if (options.results_dir.empty() && options.opencv) {
    std::cerr << "matching with " << opencv_matcher_settings(*options.opencv) << "\n";
  } else if (options.results_dir.empty()) {
    backend = std::make_unique<StereoBackend>(options.backend);
    std::cerr << "matching with the " << backend->planned() << "\n";
  }

  EvalReport report;
  report.dataset_root = options.dataset_root;
  report.method = !options.results_dir.empty() ? "files:" + options.results_dir
                  : options.opencv           ? opencv_matcher_name(*options.opencv)
                                             : method_name(options.params.method);
  report.conventions = kConventions;
  if (options.results_dir.empty() && options.opencv) {
    report.matcher = opencv_matcher_settings(*options.opencv);
  } else if (backend) {
    report.matcher = backend->planned();
    report.parameters = report_parameters(options.params);
  }
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const std::string tag = "[" + std::to_string(i + 1) + "/" + std::to_string(scenes.size()) +
                            "] " + scenes[i].name;
    report.scenes.push_back(evaluate_scene(backend.get(), scenes[i], options, tag));
  }
  // What ran, rather than what was planned, when a device fell back on some scenes.
  std::vector<std::string> paths;
  for (const SceneReport& scene : report.scenes) {
    if (!scene.matcher.empty() &&
        std::find(paths.begin(), paths.end(), scene.matcher) == paths.end()) {
      paths.push_back(scene.matcher);
    }
  }
  if (paths.size() == 1) report.matcher = paths.front();
  if (paths.size() > 1) {
    report.matcher = "several (see each scene):";
    for (const std::string& path : paths) report.matcher += " " + path + ";";
    report.matcher.pop_back();
  }

  const std::string markdown = to_markdown(report);
  write_text((fs::path(options.out_dir) / "report.md").string(), markdown);
  write_text((fs::path(options.out_dir) / "report.json").string(), to_json(report));
  std::cout << markdown;
  return 0;
}

}  // namespace flexsight

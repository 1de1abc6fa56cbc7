#include "host/eval/stereo_evaluation.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <system_error>

#include "host/eval/colorize.h"
#include "host/eval/metrics.h"
#include "host/geometry/stereo_camera.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/pfm.h"
#include "host/stereo/confidence_map.h"
#include "host/stereo/stereo_backend.h"
#include "host/stereo/stereo_pipeline.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

constexpr float kErrorMapThreshold = 2.0f;

const char* const kConventions =
    "Errors at the ground truth's resolution; 'all' = every pixel with ground truth, "
    "'nonocc' = mask 255; pixels without a result count as bad; average = unweighted mean "
    "over scenes.";

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

// `backend`: null when the results are read from files.
SceneReport evaluate_scene(StereoBackend* backend, const Scene& scene, const StereoEvalOptions& options,
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

// What ran, rather than what was planned, when a device fell back on some scenes.
void name_the_paths_that_ran(EvalReport& report) {
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
}

}  // namespace

void check_scenes_before_running(const std::vector<Scene>& scenes, const StereoEvalOptions& options) {
  for (const Scene& scene : scenes) {
    if (scene.gt_path.empty()) throw InputError(scene.left_path, "scene has no ground truth");
    if (!options.results_dir.empty()) find_result_file(options.results_dir, scene.name);
  }
}

EvalReport evaluate_stereo_scenes(const std::string& dataset_root, const std::vector<Scene>& scenes,
                                  const StereoEvalOptions& options, const BackendOptions& backend_options) {
  // The device is chosen and the kernels are built once, for every scene.
  std::unique_ptr<StereoBackend> backend;
  if (options.results_dir.empty() && options.opencv) {
    std::cerr << "matching with " << opencv_matcher_settings(*options.opencv) << "\n";
  } else if (options.results_dir.empty()) {
    backend = std::make_unique<StereoBackend>(backend_options);
    std::cerr << "matching with the " << backend->planned() << "\n";
  }

  EvalReport report;
  report.dataset_root = dataset_root;
  report.method = !options.results_dir.empty() ? "files:" + options.results_dir
                  : options.opencv           ? opencv_matcher_name(*options.opencv)
                                             : method_name(options.params.method);
  report.conventions = kConventions;
  if (options.results_dir.empty() && options.opencv) {
    report.matcher = opencv_matcher_settings(*options.opencv);
  } else if (backend) {
    report.matcher = backend->planned();
    report.parameters = options.parameters;
  }
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const std::string tag = "[" + std::to_string(i + 1) + "/" + std::to_string(scenes.size()) +
                            "] " + scenes[i].name;
    report.scenes.push_back(evaluate_scene(backend.get(), scenes[i], options, tag));
  }
  name_the_paths_that_ran(report);
  return report;
}

}  // namespace flexsight

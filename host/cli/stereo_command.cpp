// flexsight stereo: match one rectified pair (or a MiddEval3 scene folder) and write
// the disparity as PFM, optionally a colored PNG and scores against a ground truth.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "host/cli/arguments.h"
#include "host/cli/backend.h"
#include "host/cli/cloud_outputs.h"
#include "host/cli/commands.h"
#include "host/eval/colorize.h"
#include "host/eval/confidence_depth_metrics.h"
#include "host/eval/metrics.h"
#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/middeval3_files.h"
#include "host/io/middlebury_v2.h"
#include "host/io/pfm.h"
#include "host/stereo/confidence_map.h"
#include "host/stereo/pipeline_rules.h"
#include "host/stereo/stereo_pipeline.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

void print_help() {
  std::cout << "usage: flexsight stereo LEFT RIGHT -o DISP.pfm [options]\n"
               "       flexsight stereo SCENE_FOLDER -o DISP.pfm [options]\n"
               "A MiddEval3 scene folder gives im0.png, im1.png, ndisp from calib.txt and,\n"
               "when present, disp0GT.pfm and mask0nocc.png as ground truth.\n"
               "  -o DISP.pfm                 output disparity (left view, PFM)\n"
               "  --png COLOR.png             colored disparity picture\n"
               "  --raw RAW.pfm               left disparity before post-processing (PFM)\n"
               "  --raw-right RAW.pfm         right view's disparity before post-processing (PFM,\n"
               "                              right-image pixels; with --raw: the left/right check)\n"
               "  --gt GT.pfm                 ground truth: print bad-N and average error\n"
               "  --gt-mask MASK.png          non-occluded mask for --gt (255 = non-occluded)\n"
               "  --planes PLANES.pfm         per-pixel planes (a, b, c) as a 3-channel PFM\n"
               "  --conf CONF.pfm             confidence in [0, 1] (left/right agreement around the\n"
               "                              pixel x match quality, see host/stereo/confidence_map.h)\n"
               "  --conf-png CONF.png         the confidence as a picture\n"
               "  --profile                   print the device time per OpenCL kernel\n"
               "  --quiet                     no progress lines\n"
            << cloud_output_options_help() << backend_options_help()
            << "Matcher parameters:\n"
            << stereo_params_help();
}

struct StereoJob {
  std::string left;
  std::string right;
  std::string gt;
  std::string gt_mask;
  std::string calib;  // a scene folder's calib.txt
  bool ndisp_from_calib = false;
};

// Two images, or one MiddEval3 scene folder.
StereoJob resolve_inputs(const std::vector<std::string>& positional, StereoParams& params,
                         bool ndisp_given) {
  StereoJob job;
  if (positional.size() == 2) {
    job.left = positional[0];
    job.right = positional[1];
    return job;
  }
  if (positional.size() != 1) {
    throw InputError("stereo", "expected LEFT RIGHT or one scene folder, got " +
                                   std::to_string(positional.size()) + " inputs");
  }
  const fs::path scene = positional[0];
  if (!fs::is_directory(scene)) {
    throw InputError(scene.string(), "is not a scene folder (and no right image was given)");
  }
  const MiddEval3Files files = middeval3_files(scene);
  job.left = files.left;
  job.right = files.right;
  if (fs::exists(files.calib)) job.calib = files.calib;
  if (!ndisp_given) {
    params.ndisp = read_middlebury_calib(files.calib).ndisp;
    job.ndisp_from_calib = true;
  }
  if (fs::exists(files.left_truth)) job.gt = files.left_truth;
  if (fs::exists(files.nonocc_mask)) job.gt_mask = files.nonocc_mask;
  return job;
}

struct GroundTruth {
  cv::Mat disparity;  // CV_32FC1
  cv::Mat mask;       // empty: every pixel non-occluded
};

// --gt and --gt-mask, read and checked against the images before any matching, so that
// a bad file fails before an output is written.
GroundTruth load_ground_truth(const StereoJob& job, cv::Size images) {
  GroundTruth truth;
  truth.disparity = read_pfm(job.gt);
  const cv::Mat& gt = truth.disparity;
  if (gt.size() != images || gt.channels() != 1) {
    throw InputError(job.gt, "ground truth is " + std::to_string(gt.cols) + "x" + std::to_string(gt.rows) + "x" +
                                 std::to_string(gt.channels()) + ", the images " + std::to_string(images.width) +
                                 "x" + std::to_string(images.height) + "x1 disparities");
  }
  if (!job.gt_mask.empty()) truth.mask = read_mask(job.gt_mask);
  if (!truth.mask.empty() && truth.mask.size() != gt.size()) {
    throw InputError(job.gt_mask, "mask size differs from the ground truth");
  }
  return truth;
}

// `confidence` may be empty (OpenCV's matchers have none).
void print_scores(const cv::Mat& disparity, const cv::Mat& confidence, const GroundTruth& truth) {
  const cv::Mat& gt = truth.disparity;
  const cv::Mat& mask = truth.mask;
  SceneScores scores = evaluate_disparity(disparity, gt, mask);
  std::printf("\n| pixels | bad 0.5 | bad 1 | bad 2 | bad 3 | bad 4 | avg err | density |\n"
              "|---|---|---|---|---|---|---|---|\n");
  auto row = [](const char* name, const ErrorStats& s) {
    char error[32] = "n/a";
    if (std::isfinite(s.avg_error)) std::snprintf(error, sizeof error, "%.3f px", s.avg_error);
    std::printf("| %s | %.2f %% | %.2f %% | %.2f %% | %.2f %% | %.2f %% | %s | %.1f %% |\n", name,
                s.bad_percent[0], s.bad_percent[1], s.bad_percent[2], s.bad_percent[3], s.bad_percent[4], error,
                s.density_percent);
  };
  row("all", scores.all);
  if (!mask.empty()) row("nonocc", scores.nonocc);
  std::printf("(errors in pixels at this resolution; pixels without a result count as bad)\n");
  const ConfidentStats confident = evaluate_confident(disparity, gt, confidence);
  if (confident.available) {
    std::printf("confidence: sparsification AUC %.2f %% bad-2 (optimum %.2f %%); C >= 0.5 keeps "
                "%.1f %% of the pixels at %.2f %% bad-2, C >= 0.75 %.1f %% at %.2f %%\n",
                confident.sparsification_auc_percent, confident.optimal_auc_percent,
                confident.density_percent[1], confident.bad2_percent[1],
                confident.density_percent[2], confident.bad2_percent[2]);
  }
}

// --profile: device time per kernel, from the OpenCL events of the run.
void print_kernel_timings(const std::vector<opencl::KernelTiming>& timings) {
  if (timings.empty()) {
    std::cerr << "note: --profile: the reference path ran, so there are no kernel times\n";
    return;
  }
  std::printf("\n| kernel | calls | total ms | mean ms |\n|---|---|---|---|\n");
  int calls = 0;
  double seconds = 0;
  for (const opencl::KernelTiming& t : timings) {
    std::printf("| %s | %d | %.3f | %.3f |\n", t.kernel.c_str(), t.launches, t.seconds * 1e3,
                t.launches > 0 ? t.seconds * 1e3 / t.launches : 0.0);
    calls += t.launches;
    seconds += t.seconds;
  }
  std::printf("| all kernels | %d | %.3f | %.3f |\n", calls, seconds * 1e3,
              calls > 0 ? seconds * 1e3 / calls : 0.0);
}

// --profile: memory against the yardstick, the input pair (RGB8) and the planes
// of both views (a, b, c as float): 30 bytes per pixel.
void print_memory(size_t device_bytes, int width, int height) {
  const double input_and_planes = 30.0 * width * height;
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  const double rss = static_cast<double>(usage.ru_maxrss) * 1024.0;  // Linux: kilobytes
  if (device_bytes > 0) {
    std::printf("device memory: %.1f MiB at most in buffers = %.1f x the input pair and its "
                "planes (%.1f MiB)\n",
                device_bytes / 1048576.0, device_bytes / input_and_planes,
                input_and_planes / 1048576.0);
  }
  std::printf("process peak resident memory: %.1f MiB (with the OpenCL runtime's own)\n",
              rss / 1048576.0);
}

}  // namespace

int run_stereo_command(std::vector<std::string> args) {
  if (const std::optional<int> code = usage_exit_code(args, print_help)) return *code;
  StereoParams params;
  const std::optional<OpenCvMatcher> opencv = take_opencv_method(args);
  const bool ndisp_given = std::find(args.begin(), args.end(), "--ndisp") != args.end();
  consume_stereo_params(args, params);
  std::string output = take_option(args, "-o");
  if (output.empty()) output = take_option(args, "--output");
  const std::string png = take_option(args, "--png");
  const std::string raw = take_option(args, "--raw");
  const std::string raw_right = take_option(args, "--raw-right");
  const std::string planes = take_option(args, "--planes");
  const std::string conf = take_option(args, "--conf");
  const std::string conf_png = take_option(args, "--conf-png");
  CloudOutputOptions cloud_options = take_cloud_output_options(args);
  std::string gt = take_option(args, "--gt");
  std::string gt_mask = take_option(args, "--gt-mask");
  BackendOptions backend_options = take_backend_options(args);
  backend_options.profile = take_flag(args, "--profile");
  const bool quiet = take_flag(args, "--quiet");
  reject_unknown_options(args);
  if (output.empty()) throw InputError("option -o", "an output PFM path is required");

  StereoJob job = resolve_inputs(args, params, ndisp_given);
  if (!gt.empty()) job.gt = gt;
  if (!gt_mask.empty()) job.gt_mask = gt_mask;
  if (cloud_options.calib.empty()) cloud_options.calib = job.calib;
  const StereoPair pair = load_stereo_pair(job.left, job.right);
  if (!gt_mask.empty() && job.gt.empty()) throw InputError("option --gt-mask", "needs --gt");
  const GroundTruth truth = job.gt.empty() ? GroundTruth{} : load_ground_truth(job, pair.left.size());
  if (job.ndisp_from_calib) std::cerr << "ndisp " << params.ndisp << " from calib.txt\n";

  ProgressCallback progress;
  if (!quiet) progress = [](const std::string& stage) { std::cerr << "  " << stage << "\n"; };
  validate_inputs(pair.left, pair.right, params);  // before the kernels are built
  check_cloud_outputs(cloud_options, pair.left.cols, pair.left.rows);
  if (opencv && (!raw.empty() || !raw_right.empty() || !planes.empty() || !conf.empty() ||
                 !conf_png.empty() || backend_options.profile)) {
    throw InputError("option --method", std::string(opencv_matcher_name(*opencv)) +
                                            " gives a disparity only: no --raw, --raw-right, "
                                            "--planes, --conf, --conf-png or --profile");
  }
  if (opencv) check_opencv_matcher_size(*opencv, pair.left.size(), params.ndisp, job.left + " and " + job.right);
  // Every output's folder is checked before the matching, so that a mistyped path fails
  // in a second, not after the run with some of the outputs written.
  for (const std::string& path : {output, png, raw, raw_right, planes, conf, conf_png,
                                  cloud_options.ply, cloud_options.depth, cloud_options.render}) {
    if (path.empty()) continue;
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder)) {
      throw InputError(path, "cannot be written: its folder does not exist");
    }
  }
  std::string used;
  StereoResult result;
  std::unique_ptr<StereoBackend> backend;
  if (opencv) {
    used = opencv_matcher_settings(*opencv);
    std::cerr << opencv_matcher_name(*opencv) << " on " << pair.left.cols << "x"
              << pair.left.rows << ", ndisp " << params.ndisp << "\n";
    const auto start = std::chrono::steady_clock::now();
    result.disparity = run_opencv_matcher(*opencv, pair.left, pair.right, params.ndisp);
    result.timings.push_back(
        {opencv_matcher_name(*opencv),
         std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
  } else {
    backend = std::make_unique<StereoBackend>(backend_options);
    std::cerr << method_name(params.method) << " on " << pair.left.cols << "x" << pair.left.rows
              << ", ndisp " << params.ndisp << ", " << backend->planned() << "\n";
    result = backend->run(pair.left, pair.right, params, progress, &used);
  }

  write_pfm(output, result.disparity);
  if (!raw.empty()) write_pfm(raw, result.raw_left);
  if (!raw_right.empty()) write_pfm(raw_right, result.raw_right);
  if (!planes.empty()) write_pfm(planes, result.planes_left);
  cv::Mat confidence;
  if (!opencv &&
      (!conf.empty() || !conf_png.empty() || cloud_options.wants_3d() || !job.gt.empty())) {
    confidence = confidence_map(result, pair.left, params);
  }
  if (!conf.empty()) write_pfm(conf, confidence);
  if (!conf_png.empty()) write_image(conf_png, colorize_confidence(confidence));
  if (!png.empty()) {
    write_image(png, colorize_disparity(result.disparity, static_cast<float>(params.ndisp)));
  }
  std::printf("| stage (%s) | seconds |\n|---|---|\n", used.c_str());
  for (const StageTiming& t : result.timings) std::printf("| %s | %.3f |\n", t.stage.c_str(), t.seconds);
  std::printf("| total | %.3f |\n", result.total_seconds());
  if (backend_options.profile) {
    print_kernel_timings(backend->kernel_timings());
    print_memory(backend->peak_device_bytes(), pair.left.cols, pair.left.rows);
  }
  std::printf("wrote %s%s%s\n", output.c_str(), png.empty() ? "" : " and ", png.c_str());
  write_cloud_outputs(cloud_options, result.disparity, pair.left, result.planes_left, confidence);
  if (!job.gt.empty()) print_scores(result.disparity, confidence, truth);
  return 0;
}

}  // namespace flexsight

// flexsight stereo: match one rectified pair (or a MiddEval3 scene folder) and write
// the disparity as PFM, optionally a colored PNG and scores against a ground truth.
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
#include "host/cli/stereo_tables.h"
#include "host/eval/colorize.h"
#include "host/eval/metrics.h"
#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/output_path.h"
#include "host/io/middeval3_files.h"
#include "host/io/middlebury_v2.h"
#include "host/io/pfm.h"
#include "host/stereo/confidence_map.h"
#include "host/stereo/pipeline_rules.h"
#include "host/stereo/stereo_backend.h"
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

// The files the matcher's results go to (empty: not written).
struct StereoOutputs {
  std::string output, png, raw, raw_right, planes, conf, conf_png;
};

StereoOutputs take_stereo_outputs(std::vector<std::string>& args) {
  StereoOutputs out;
  out.output = take_option(args, "-o");
  if (out.output.empty()) out.output = take_option(args, "--output");
  take_options(args, {{"--png", &out.png},
                      {"--raw", &out.raw},
                      {"--raw-right", &out.raw_right},
                      {"--planes", &out.planes},
                      {"--conf", &out.conf},
                      {"--conf-png", &out.conf_png}});
  return out;
}

// What OpenCV's matchers cannot give.
void check_opencv_outputs(const StereoOutputs& out, const std::optional<OpenCvMatcher>& opencv, bool profile) {
  if (opencv && (!out.raw.empty() || !out.raw_right.empty() || !out.planes.empty() || !out.conf.empty() ||
                 !out.conf_png.empty() || profile)) {
    throw InputError("option --method", std::string(opencv_matcher_name(*opencv)) +
                                            " gives a disparity only: no --raw, --raw-right, "
                                            "--planes, --conf, --conf-png or --profile");
  }
}

// Every output's folder is checked before the matching, so that a mistyped path fails
// in a second, not after the run with some of the outputs written.
void check_output_folders(const StereoOutputs& out, const CloudOutputOptions& cloud_options) {
  for (const std::string& path : {out.output, out.png, out.raw, out.raw_right, out.planes, out.conf, out.conf_png,
                                  cloud_options.ply, cloud_options.depth, cloud_options.render}) {
    check_output_file(path);
  }
}

// OpenCV's matcher, timed as one stage; `used` receives its settings.
StereoResult run_opencv(OpenCvMatcher opencv, const StereoPair& pair, const StereoParams& params, std::string* used) {
  StereoResult result;
  *used = opencv_matcher_settings(opencv);
  std::cerr << opencv_matcher_name(opencv) << " on " << pair.left.cols << "x" << pair.left.rows << ", ndisp "
            << params.ndisp << "\n";
  const auto start = std::chrono::steady_clock::now();
  result.disparity = run_opencv_matcher(opencv, pair.left, pair.right, params.ndisp);
  result.timings.push_back(
      {opencv_matcher_name(opencv), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
  return result;
}

// The disparity, raw, planes, confidence and picture files asked for; the confidence map
// (empty for OpenCV's matchers, or when nothing needs it).
cv::Mat write_stereo_outputs(const StereoOutputs& out, const StereoResult& result, const StereoPair& pair,
                             const StereoParams& params, bool confidence_needed) {
  write_pfm(out.output, result.disparity);
  if (!out.raw.empty()) write_pfm(out.raw, result.raw_left);
  if (!out.raw_right.empty()) write_pfm(out.raw_right, result.raw_right);
  if (!out.planes.empty()) write_pfm(out.planes, result.planes_left);
  cv::Mat confidence;
  if (confidence_needed) confidence = confidence_map(result, pair.left, params);
  if (!out.conf.empty()) write_pfm(out.conf, confidence);
  if (!out.conf_png.empty()) write_image(out.conf_png, colorize_confidence(confidence));
  if (!out.png.empty()) {
    write_image(out.png, colorize_disparity(result.disparity, static_cast<float>(params.ndisp)));
  }
  return confidence;
}

}  // namespace

int run_stereo_command(std::vector<std::string> args) {
  if (const std::optional<int> code = usage_exit_code(args, print_help)) return *code;
  StereoParams params;
  const std::optional<OpenCvMatcher> opencv = take_opencv_method(args);
  const bool ndisp_given = std::find(args.begin(), args.end(), "--ndisp") != args.end();
  consume_stereo_params(args, params);
  const StereoOutputs out = take_stereo_outputs(args);
  CloudOutputOptions cloud_options = take_cloud_output_options(args);
  std::string gt = take_option(args, "--gt");
  std::string gt_mask = take_option(args, "--gt-mask");
  BackendOptions backend_options = take_backend_options(args);
  backend_options.profile = take_flag(args, "--profile");
  const bool quiet = take_flag(args, "--quiet");
  reject_unknown_options(args);
  if (out.output.empty()) throw InputError("option -o", "an output PFM path is required");

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
  check_opencv_outputs(out, opencv, backend_options.profile);
  if (opencv) check_opencv_matcher_size(*opencv, pair.left.size(), params.ndisp, job.left + " and " + job.right);
  check_output_folders(out, cloud_options);
  std::string used;
  StereoResult result;
  std::unique_ptr<StereoBackend> backend;
  if (opencv) {
    result = run_opencv(*opencv, pair, params, &used);
  } else {
    backend = std::make_unique<StereoBackend>(backend_options);
    std::cerr << method_name(params.method) << " on " << pair.left.cols << "x" << pair.left.rows
              << ", ndisp " << params.ndisp << ", " << backend->planned() << "\n";
    result = backend->run(pair.left, pair.right, params, progress, &used);
  }

  const bool confidence_needed =
      !opencv && (!out.conf.empty() || !out.conf_png.empty() || cloud_options.wants_3d() || !job.gt.empty());
  const cv::Mat confidence = write_stereo_outputs(out, result, pair, params, confidence_needed);
  print_stage_times(used, result);
  if (backend_options.profile) {
    print_kernel_timings(backend->kernel_timings());
    print_memory(backend->peak_device_bytes(), pair.left.cols, pair.left.rows);
  }
  std::printf("wrote %s%s%s\n", out.output.c_str(), out.png.empty() ? "" : " and ", out.png.c_str());
  write_cloud_outputs(cloud_options, result.disparity, pair.left, result.planes_left, confidence);
  if (!job.gt.empty()) print_scores(result.disparity, confidence, truth.disparity, truth.mask);
  return 0;
}

}  // namespace flexsight

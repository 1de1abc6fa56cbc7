// flexsight projector decode|check|calibrate: the projector as a third view
// (docs/projector.md). decode fills the left pixels a stereo result leaves inconsistent
// from the projector's pattern; check flags stereo matches the pattern disagrees with;
// calibrate estimates the pattern (and checks the projector's pose) from
// confident stereo results. Both read what `flexsight stereo -o --raw --raw-right` wrote.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "host/cli/arguments.h"
#include "host/cli/commands.h"
#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/middeval3_files.h"
#include "host/io/output_path.h"
#include "host/io/pfm.h"
#include "host/projector/projector_calibrate.h"
#include "host/projector/projector_check.h"
#include "host/projector/projector_decode.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

void print_help() {
  std::cout << "usage: flexsight projector decode SCENE --stereo DIR -o DISP.pfm [options]\n"
               "       flexsight projector check SCENE --stereo DIR --mask MASK.png [-o DISP.pfm] [options]\n"
               "       flexsight projector calibrate SCENE [SCENE ...] --stereo DIR -o OUT_DIR [options]\n"
               "SCENE is a MiddEval3 scene folder (im0.png, calib.txt); DIR holds its stereo result\n"
               "as <scene>_disp.pfm, <scene>_raw.pfm, <scene>_raw_right.pfm (flexsight stereo's -o,\n"
               "--raw and --raw-right).\n"
               "decode: the pixels failing the left/right check are searched along the\n"
               "camera-projector rows; the distinct ones get the decoded disparity.\n"
               "  --projector CALIB     calib.txt whose proj* lines give the projector and pattern\n"
               "                        (default: the scene's calib.txt)\n"
               "  --window N            odd window, px (default 13)\n"
               "  --min-score S         least ZNCC of the best candidate (default 0.5)\n"
               "  --min-margin M        best minus the best elsewhere (default 0.1)\n"
               "  --peak K              candidates either side of the best that belong to its peak (default 4)\n"
               "  --min-texture T       least spread of the window's projector light, grey levels (default 1)\n"
               "  --slanted             also try windows of slanted surfaces (s_x 0, 0.5, 1; s_y -1, 0, 1)\n"
               "  --visibility          skip candidates the stereo result rules out: in front of\n"
               "                        what the right camera sees there, or in a projector shadow\n"
               "  --state STATE.png     0 not asked, 128 not distinct, 255 decoded\n"
               "check: at each pixel of <scene>_disp.pfm the projector's light is compared with the\n"
               "pattern at the stereo disparity and within +-range px along the projector row;\n"
               "writes MASK.png (255 where the projector disagrees) and, with -o, the disparity\n"
               "with those pixels inf (or, with --replace, the projector's best where distinct).\n"
               "  --projector CALIB     as for decode\n"
               "  --window N            odd window, px (default 13)\n"
               "  --range R             px either side of the stereo disparity searched (default 8)\n"
               "  --margin M            flag when the best more than 2 px away scores M above the\n"
               "                        stereo disparity (default 0.3)\n"
               "  --floor F             also flag when the stereo disparity scores below F (default -1: off)\n"
               "  --min-texture T       as for decode (default 1)\n"
               "  --replace             flagged pixels take the projector's best when it scores at\n"
               "                        least --replace-score (default 0.5); the others inf\n"
               "calibrate: estimates the pattern from the confident stereo matches of the scenes,\n"
               "for a projector on the baseline; writes OUT_DIR/calib.txt (the first scene's with\n"
               "the proj* lines) and OUT_DIR/projector_pattern.png, and prints the pose check.\n"
               "  --fov DEG             the projector's square field (default 35)\n"
               "  --offset MM           its distance from the middle of the baseline along x (default 0)\n"
               "  --scan MM             also try offsets within +-MM in steps of MM/4 (pose check)\n";
}

struct SceneInputs {
  std::string name;
  MiddleburyCalib calib;
  cv::Mat left, disparity, raw_left, raw_right;
};

void same_size(const std::string& path, const cv::Mat& image, const cv::Mat& left) {
  if (image.size() != left.size()) throw InputError(path, "is not the size of the scene's im0.png");
}

// with_raw: also the raw left and right disparities (decode and calibrate need them).
SceneInputs read_scene(const std::string& folder, const std::string& stereo_dir, bool with_raw = true) {
  SceneInputs scene;
  scene.name = fs::path(folder).filename().string();
  if (scene.name.empty()) scene.name = fs::path(folder).parent_path().filename().string();
  const MiddEval3Files files = middeval3_files(folder);
  scene.calib = read_middlebury_calib(files.calib);
  scene.left = load_rgb8(files.left);
  const auto read = [&](const std::string& suffix) {
    const std::string path = (fs::path(stereo_dir) / (scene.name + suffix)).string();
    cv::Mat image = read_pfm(path);
    same_size(path, image, scene.left);
    return image;
  };
  scene.disparity = read("_disp.pfm");
  if (with_raw) {
    scene.raw_left = read("_raw.pfm");
    scene.raw_right = read("_raw_right.pfm");
  }
  return scene;
}

// The calibration carrying the projector: --projector's file, else the scene's; one that
// has none or whose projector the decoder cannot use is an InputError naming the file.
MiddleburyCalib read_projector(const std::string& folder, const std::string& projector_file,
                               const MiddleburyCalib& scene_calib) {
  const std::string source = projector_file.empty() ? middeval3_files(folder).calib : projector_file;
  MiddleburyCalib with_projector = projector_file.empty() ? scene_calib : read_middlebury_calib(projector_file);
  if (!with_projector.projector) {
    throw InputError(source, "has no projector entry (proj* lines, docs/projector.md); give --projector");
  }
  require_rectified_projector(*with_projector.projector, source);
  return with_projector;
}

void require_odd_window(int window) {
  if (window < 3 || window % 2 == 0 || window > 51) throw InputError("option --window", "must be odd, 3..51");
}

int run_decode(std::vector<std::string>& args) {
  const std::string stereo_dir = take_option(args, "--stereo");
  const std::string out = take_option(args, "-o");
  const std::string projector_file = take_option(args, "--projector");
  const std::string state_png = take_option(args, "--state");
  ProjectorDecodeParams params;
  params.window = int(take_number_option(args, "--window", params.window));
  params.min_score = take_number_option(args, "--min-score", params.min_score);
  params.min_margin = take_number_option(args, "--min-margin", params.min_margin);
  params.peak_halfwidth = int(take_number_option(args, "--peak", params.peak_halfwidth));
  params.min_texture = take_number_option(args, "--min-texture", params.min_texture);
  params.slanted = take_flag(args, "--slanted");
  params.visibility = take_flag(args, "--visibility");
  reject_unknown_options(args);
  if (args.size() != 1) throw InputError("projector decode", "expected one SCENE folder");
  if (stereo_dir.empty()) throw InputError("option --stereo", "is required");
  if (out.empty()) throw InputError("option -o", "is required");
  require_odd_window(params.window);
  check_output_file(out);
  if (!state_png.empty()) check_output_file(state_png);

  const SceneInputs scene = read_scene(args[0], stereo_dir);
  const MiddleburyCalib with_projector = read_projector(args[0], projector_file, scene.calib);
  const cv::Mat pattern = load_pattern(*with_projector.projector);

  const cv::Mat asked = left_right_failures(scene.raw_left, scene.raw_right, params.lr_tolerance);
  const ProjectorDecodeResult result = decode_with_projector(scene.left, scene.disparity, asked, scene.calib,
                                                             *with_projector.projector, pattern, params,
                                                             scene.raw_left, scene.raw_right);
  write_pfm(out, result.disparity);
  if (!state_png.empty()) {
    cv::Mat picture = result.state.clone();
    picture.setTo(255, result.state == 1);
    picture.setTo(128, result.state == 2);
    write_image(state_png, picture);
  }
  std::printf("%s: %d pixels failed the left/right check, %d decoded (%.1f %%)\n", scene.name.c_str(),
              result.asked, result.decoded, result.asked ? 100.0 * result.decoded / result.asked : 0.0);
  return 0;
}

int run_check(std::vector<std::string>& args) {
  const std::string stereo_dir = take_option(args, "--stereo");
  const std::string mask_png = take_option(args, "--mask");
  const std::string out = take_option(args, "-o");
  const std::string projector_file = take_option(args, "--projector");
  ProjectorCheckParams params;
  params.window = int(take_number_option(args, "--window", params.window));
  params.range = take_number_option(args, "--range", params.range);
  params.margin = take_number_option(args, "--margin", params.margin);
  params.floor = take_number_option(args, "--floor", params.floor);
  params.min_texture = take_number_option(args, "--min-texture", params.min_texture);
  params.replace = take_flag(args, "--replace");
  params.replace_score = take_number_option(args, "--replace-score", params.replace_score);
  reject_unknown_options(args);
  if (args.size() != 1) throw InputError("projector check", "expected one SCENE folder");
  if (stereo_dir.empty()) throw InputError("option --stereo", "is required");
  if (mask_png.empty()) throw InputError("option --mask", "is required");
  require_odd_window(params.window);
  if (!(params.range > 2.0 && params.range <= 64.0)) throw InputError("option --range", "must be in (2, 64] px");
  if (!(params.margin > 0.0 && params.margin <= 2.0)) throw InputError("option --margin", "must be in (0, 2]");
  if (!(params.floor >= -1.0 && params.floor <= 1.0)) throw InputError("option --floor", "must be in [-1, 1]");
  if (!(params.replace_score >= -1.0 && params.replace_score <= 1.0)) {
    throw InputError("option --replace-score", "must be in [-1, 1]");
  }
  check_output_file(mask_png);
  if (!out.empty()) check_output_file(out);

  const SceneInputs scene = read_scene(args[0], stereo_dir, false);
  const MiddleburyCalib with_projector = read_projector(args[0], projector_file, scene.calib);
  const cv::Mat pattern = load_pattern(*with_projector.projector);
  const ProjectorCheckResult result =
      check_with_projector(scene.left, scene.disparity, scene.calib, *with_projector.projector, pattern, params);
  write_image(mask_png, result.flagged);
  if (!out.empty()) write_pfm(out, result.disparity);
  std::printf("%s: %d pixels checked, %d flagged (%.1f %%), %d replaced\n", scene.name.c_str(), result.checked,
              result.flagged_count, result.checked ? 100.0 * result.flagged_count / result.checked : 0.0,
              result.replaced);
  return 0;
}

int run_calibrate(std::vector<std::string>& args) {
  const std::string stereo_dir = take_option(args, "--stereo");
  const std::string out = take_option(args, "-o");
  const double fov = take_number_option(args, "--fov", 35.0);
  const double offset = take_number_option(args, "--offset", 0.0);
  const double scan = take_number_option(args, "--scan", 0.0);
  reject_unknown_options(args);
  if (args.empty()) throw InputError("projector calibrate", "expected at least one SCENE folder");
  if (scan > 0 && args.size() < 2) throw InputError("option --scan", "needs at least two scenes");
  if (stereo_dir.empty()) throw InputError("option --stereo", "is required");
  if (out.empty()) throw InputError("option -o", "is required");
  if (!(fov > 0 && fov < 170)) throw InputError("option --fov", "must be in (0, 170) degrees");
  if (!(scan >= 0)) throw InputError("option --scan", "must not be negative");
  if (fs::exists(out) && !fs::is_empty(out)) throw InputError("option -o", out + " exists and is not empty");
  if (!fs::exists(fs::absolute(out).parent_path())) throw InputError("option -o", "the parent folder of " + out + " does not exist");

  std::vector<SceneInputs> scenes;
  for (const std::string& folder : args) scenes.push_back(read_scene(folder, stereo_dir));
  std::vector<CalibrationView> views;
  for (const SceneInputs& scene : scenes) {
    const cv::Mat failed = left_right_failures(scene.raw_left, scene.raw_right, 0.5f);
    views.push_back(calibration_view(scene.left, scene.disparity, failed == 0, scene.calib));
  }
  if (scan > 0) {
    std::printf("pose check: agreement of the patterns from the even and the odd scenes\n| offset (mm) | agreement |\n|---|---|\n");
    for (double o = offset - scan; o <= offset + scan + 1e-9; o += scan / 4) {
      const ProjectorCalib candidate = projector_on_baseline(scenes[0].calib, fov, o, "");
      std::printf("| %.1f | %.3f |\n", o, split_agreement(views, candidate));
    }
  }
  const ProjectorCalib projector = projector_on_baseline(scenes[0].calib, fov, offset, "projector_pattern.png");
  const PatternEstimate estimate = estimate_pattern(views, projector);
  std::printf("even/odd agreement at offset %.1f mm: %.3f\n", offset, split_agreement(views, projector));
  std::printf("coverage: %.1f %% of the pattern the left camera can reach\n",
              100.0 * pattern_coverage(estimate, scenes[0].calib, projector));
  if (scenes[0].calib.projector) {  // a known pattern: how close the estimate came
    const cv::Mat truth = load_pattern(*scenes[0].calib.projector);
    if (truth.size() == estimate.mean.size()) {
      const cv::Mat everywhere(truth.size(), CV_32FC1, cv::Scalar(1));
      std::printf("agreement with %s: %.3f\n", scenes[0].calib.projector->pattern_path.c_str(),
                  pattern_agreement(estimate.mean, estimate.weight, truth, everywhere));
    }
  }
  fs::create_directories(out);
  write_image((fs::path(out) / "projector_pattern.png").string(), estimate.image8());
  std::ofstream calib((fs::path(out) / "calib.txt").string());
  calib << calib_text_without_projector(middeval3_files(args[0]).calib) << projector_calib_text(projector);
  if (!calib.flush()) throw InputError(out + "/calib.txt", "cannot be written");
  std::printf("wrote %s/calib.txt and projector_pattern.png from %zu scenes\n", out.c_str(), scenes.size());
  return 0;
}

}  // namespace

int run_projector_command(std::vector<std::string> args) {
  if (const std::optional<int> code = usage_exit_code(args, print_help)) return *code;
  if (args.empty()) {
    print_help();
    return 1;
  }
  const std::string mode = args.front();
  args.erase(args.begin());
  if (mode == "decode") return run_decode(args);
  if (mode == "check") return run_check(args);
  if (mode == "calibrate") return run_calibrate(args);
  throw InputError("projector", "unknown mode '" + mode + "' (decode, check or calibrate)");
}

}  // namespace flexsight

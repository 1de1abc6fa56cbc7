// flexsight pick: a rectified stereo pair in, the parts in the bin out, ranked for the
// robot (host/cli/pick_pipeline.h; docs/pick.md).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "host/cli/arguments.h"
#include "host/cli/backend.h"
#include "host/cli/commands.h"
#include "host/cli/pick_outputs.h"
#include "host/cli/pick_pipeline.h"
#include "host/cli/pose_inputs.h"
#include "host/detect/detector_model.h"
#include "host/io/atomic_file.h"
#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/stereo/pipeline_rules.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

void print_help() {
  std::cout
      << "usage: flexsight pick LEFT RIGHT --calib C --templates T [options]\n"
         "       flexsight pick SCENE_DIR --templates T [options]   (im0.png, im1.png, calib.txt)\n"
         "Stereo depth of the rectified pair, the parts detected in the left image, the 6D pose\n"
         "of each, and the parts ranked for a robot to take (best first).\n"
         "  --calib C          the pair's calibration (Middlebury calib.txt, KITTI, OpenCV\n"
         "                     YAML/XML with Q); ndisp from a calib.txt unless --ndisp\n"
         "  --templates T      the parts' edge templates (flexsight pose-templates CAD_DIR -o T)\n"
         "  --cad DIR          the CAD models the templates were made from (default:\n"
         "                     " << default_pose_cad_dir() << ")\n"
         "  --model M.onnx     the detector (default: the shipped one, "
      << default_detector_model_path() << ")\n"
         "  -o PICKS.json      the ranked parts (docs/pick.md); without it a table only\n"
         "  --png P.png        the left image with the boxes and the parts' outlines\n"
         "  --score S          detections scoring above S are posed (default 0.3)\n"
         "  --threads N        parts posed at once (default: all cores)\n"
         "  --quiet            no progress lines\n"
         "  --ndisp N and the stereo parameters of flexsight stereo; --preset active (for\n"
         "                     projector-lit pairs) unless another --preset is given\n"
      << backend_options_help();
}

struct PickInputs {
  std::string left, right, calib;
};

PickInputs resolve_pick_inputs(const std::vector<std::string>& positional, const std::string& calib) {
  PickInputs inputs;
  inputs.calib = calib;
  if (positional.size() == 2) {
    inputs.left = positional[0];
    inputs.right = positional[1];
  } else if (positional.size() == 1 && fs::is_directory(positional[0])) {
    const fs::path scene = positional[0];
    inputs.left = (scene / "im0.png").string();
    inputs.right = (scene / "im1.png").string();
    if (inputs.calib.empty()) inputs.calib = (scene / "calib.txt").string();
  } else {
    throw InputError("pick", positional.size() == 1 ? positional[0] + " is not a scene folder (and no right image was given)"
                                                    : "expected LEFT RIGHT or one scene folder, got " +
                                                          std::to_string(positional.size()) + " inputs");
  }
  if (inputs.calib.empty()) throw InputError("option --calib", "missing: the pair's calibration");
  return inputs;
}

void check_output_folder(const std::string& path, const std::string& option) {
  if (path.empty()) return;
  const fs::path folder = fs::path(path).parent_path();
  if (!folder.empty() && !fs::is_directory(folder)) {
    throw InputError(option + " " + path, "cannot be written: its folder does not exist");
  }
}

void print_table(const PickResult& result) {
  std::printf("| rank | obj | pick score | pose score | visible | height mm | x mm | y mm | z mm |\n"
              "|---|---|---|---|---|---|---|---|---|\n");
  int rank = 1;
  for (const PickCandidate& c : result.picks) {
    std::printf("| %d | %d | %.3f | %.3f | %.2f | %.1f | %.1f | %.1f | %.1f |\n", rank++, c.obj_id, c.pick_score,
                c.pose_score, c.visible_fraction, c.height_mm, c.pose.t.x(), c.pose.t.y(), c.pose.t.z());
  }
  const PickStageSeconds& s = result.seconds;
  std::printf("\n| stage | seconds |\n|---|---|\n| stereo (%s) | %.3f |\n| depth | %.3f |\n"
              "| detection | %.3f |\n| pose (%zu parts) | %.3f |\n| ranking | %.3f |\n| total | %.3f |\n",
              result.stereo_path.c_str(), s.stereo, s.depth, s.detection, result.picks.size(), s.pose, s.ranking,
              s.total());
}

}  // namespace

int run_pick_command(std::vector<std::string> args) {
  if (auto code = usage_exit_code(args, print_help)) return *code;
  PickSettings settings;
  const bool ndisp_given = std::find(args.begin(), args.end(), "--ndisp") != args.end();
  // The camera's own scene is projector-lit: the active preset unless one is named.
  if (std::find(args.begin(), args.end(), "--preset") == args.end()) apply_stereo_preset("active", settings.stereo);
  consume_stereo_params(args, settings.stereo);
  settings.backend = take_backend_options(args);
  const std::string calib_option = take_option(args, "--calib");
  settings.templates = take_option(args, "--templates");
  settings.cad = take_option(args, "--cad");
  settings.model = resolve_detector_model_path(take_option(args, "--model"));
  const std::string output = take_option(args, "-o");
  const std::string png = take_option(args, "--png");
  const double score = take_number_option(args, "--score", 0.3);
  const std::string threads = take_option(args, "--threads");
  settings.quiet = take_flag(args, "--quiet");
  reject_unknown_options(args);
  if (!(score >= 0.0 && score <= 1.0)) throw InputError("option --score", "must lie in [0, 1]");
  settings.detector.score_threshold = static_cast<float>(score);
  if (!threads.empty()) settings.threads = static_cast<int>(parse_whole_number("--threads", threads, 1, 1024));
  if (settings.templates.empty()) {
    throw InputError("option --templates", "missing (make them once with flexsight pose-templates CAD_DIR -o FILE)");
  }
  if (settings.cad.empty()) settings.cad = default_pose_cad_dir();
  const PickInputs inputs = resolve_pick_inputs(args, calib_option);
  check_output_folder(output, "-o");
  check_output_folder(png, "--png");

  // Every input is read and checked before the work: the pair, the calibration against
  // it, the stereo parameters, then the detector, templates and CAD models.
  const StereoPair pair = load_stereo_pair(inputs.left, inputs.right);
  const StereoCamera rig = read_stereo_camera(inputs.calib).resized_to(pair.left.cols, pair.left.rows);
  if (!ndisp_given) {
    try {
      settings.stereo.ndisp = read_middlebury_calib(inputs.calib).ndisp;
    } catch (const InputError&) {
      throw InputError("option --ndisp", "missing: " + inputs.calib + " gives no disparity range");
    }
  }
  validate_inputs(pair.left, pair.right, settings.stereo);
  PickPipeline pipeline(settings);
  if (!settings.quiet) std::cerr << "pick: " << pair.left.cols << "x" << pair.left.rows << ", ndisp " << settings.stereo.ndisp << "\n";

  const PickResult result = pipeline.run(pair.left, pair.right, rig);
  if (!output.empty()) {
    const std::string json =
        pick_json(result, {inputs.left, inputs.right, inputs.calib, settings.model, settings.templates, settings.cad});
    write_atomically(output, [&](const std::string& tmp) {
      std::ofstream out(tmp);
      out << json;
      if (!out) throw InputError(output, "cannot be written");
    });
  }
  if (!png.empty()) write_image(png, [&] {
    cv::Mat rgb;
    cv::cvtColor(pick_picture(pair.left, result, pipeline.models()), rgb, cv::COLOR_BGR2RGB);
    return rgb;
  }());
  print_table(result);
  return 0;
}

}  // namespace flexsight

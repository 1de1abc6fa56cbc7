// flexsight pick: a rectified stereo pair in, the parts in the bin out, ranked for the
// robot (host/pick/pick_session.h; docs/pick.md).
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgproc.hpp>

#include "host/cli/arguments.h"
#include "host/cli/backend.h"
#include "host/cli/commands.h"
#include "host/cli/pick_options.h"
#include "host/detect/detector_model.h"
#include "host/io/atomic_file.h"
#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/output_path.h"
#include "host/io/middeval3_files.h"
#include "host/pick/pick_inputs.h"
#include "host/pick/pick_outputs.h"
#include "host/pick/pick_session.h"
#include "host/pose/pose_models.h"
#include "host/stereo/pipeline_rules.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

void print_help() {
  std::cout << "usage: flexsight pick LEFT RIGHT --calib C --templates T [options]\n"
               "       flexsight pick SCENE_DIR --templates T [options]   (im0.png, im1.png, calib.txt,\n"
               "                                                           im0_passive.png if there)\n"
               "Stereo depth of the rectified pair, the parts detected in the left image, the 6D pose\n"
               "of each, and the parts ranked for a robot to take (best first).\n"
               "  --calib C          the pair's calibration (Middlebury calib.txt, KITTI, OpenCV\n"
               "                     YAML/XML with Q); ndisp from a calib.txt unless --ndisp\n"
               "  -o PICKS.json      the ranked parts (docs/pick.md); without it a table only\n"
               "  --png P.png        the left image with the boxes and the parts' outlines\n"
               "  --passive-left P   the left view with the projector off (the same size): detection\n"
               "                     and the pose's edges use it; the dots hide parts from the\n"
               "                     detector and are edges themselves\n"
            << pick_mode_options_help() << pick_options_help();
}

PickInputFiles resolve_pick_inputs(const std::vector<std::string>& positional, const std::string& calib,
                                   const std::string& passive_left) {
  PickInputFiles inputs;
  inputs.calib = calib;
  inputs.passive_left = passive_left;
  if (positional.size() == 2) {
    inputs.left = positional[0];
    inputs.right = positional[1];
  } else if (positional.size() == 1 && fs::is_directory(positional[0])) {
    const fs::path scene = positional[0];
    const MiddEval3Files files = middeval3_files(scene);
    inputs.left = files.left;
    inputs.right = files.right;
    if (inputs.calib.empty()) inputs.calib = files.calib;
    if (inputs.passive_left.empty() && fs::is_regular_file(files.left_passive)) {
      inputs.passive_left = files.left_passive;
    }
  } else {
    throw InputError("pick", positional.size() == 1 ? positional[0] + " is not a scene folder (and no right image was given)"
                                                    : "expected LEFT RIGHT or one scene folder, got " +
                                                          std::to_string(positional.size()) + " inputs");
  }
  if (inputs.calib.empty()) throw InputError("option --calib", "missing: the pair's calibration");
  return inputs;
}

void print_table(const PickResult& result) {
  if (result.has_first_pick) {
    const PickCandidate& c = result.first_pick;
    std::printf("first pick (mode %s): obj %d at %.1f %.1f %.1f mm, %s, after %.3f s\n\n", pick_mode_name(result.mode),
                c.obj_id, c.pose.t.x(), c.pose.t.y(), c.pose.t.z(),
                result.first_pick_accepted ? "accepted" : "none accepted, the best-ranked", result.seconds_to_first_pick);
  }
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
  PickOptions options = take_pick_options(args);
  PickSettings& settings = options.settings;
  take_pick_mode_options(args, settings);
  const std::string calib_option = take_option(args, "--calib");
  const std::string output = take_option(args, "-o");
  const std::string png = take_option(args, "--png");
  const std::string passive_left = take_option(args, "--passive-left");
  reject_unknown_options(args);
  const PickInputFiles inputs = resolve_pick_inputs(args, calib_option, passive_left);
  check_output_file(output);
  check_output_file(png);

  // Every input is read and checked before the work: the pair, the calibration against
  // it, the stereo parameters, then the detector, templates and CAD models.
  const PickInputImages images = read_pick_inputs(inputs, settings.detection_tile);
  const StereoPair& pair = images.pair;
  const cv::Mat& passive = images.passive;
  settings.stereo.ndisp = pick_ndisp(options, inputs.calib);
  validate_inputs(pair.left, pair.right, settings.stereo);
  PickSession session(settings);
  if (!settings.quiet) std::cerr << "pick: " << pair.left.cols << "x" << pair.left.rows << ", ndisp " << settings.stereo.ndisp << "\n";

  const PickResult result = session.pick(pair.left, pair.right, images.rig, passive);
  if (!output.empty()) {
    const std::string json =
        pick_json(result, {inputs.left, inputs.right, inputs.calib, settings.model, settings.templates, settings.cad,
                           inputs.passive_left, settings.detector.parts.obj_ids});
    write_atomically(output, [&](const std::string& tmp) {
      std::ofstream out(tmp);
      out << json;
      if (!out) throw InputError(output, "cannot be written (" + std::string(std::strerror(errno)) + ")");
    });
  }
  if (!png.empty()) write_image(png, [&] {
    cv::Mat rgb;
    cv::cvtColor(pick_picture(passive.empty() ? pair.left : passive, result, session.models()), rgb, cv::COLOR_BGR2RGB);
    return rgb;
  }());
  print_table(result);
  return 0;
}

}  // namespace flexsight

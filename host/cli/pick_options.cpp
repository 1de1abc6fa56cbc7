#include "host/cli/pick_options.h"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "host/cli/arguments.h"
#include "host/cli/backend.h"
#include "host/cli/pick_namer_option.h"
#include "host/detect/detector_model.h"
#include "host/io/calibration.h"
#include "host/io/input_error.h"
#include "host/dataset/detection_data.h"
#include "host/detect/known_parts.h"
#include "host/pose/edge_thresholds.h"
#include "host/pose/pose_models.h"

namespace flexsight {
namespace {

// Pick poses the detections above this (the best five classes per box) and keeps the
// best-fitting pose where boxes overlap: on bins the detector's right class scores
// 0.03-0.3 for half of the parts (docs/pick.md), and a wrong class fits worse.
constexpr double kPickDetectionScore = 0.03;

}  // namespace

PickOptions take_pick_options(std::vector<std::string>& args) {
  PickOptions options;
  PickSettings& settings = options.settings;
  options.ndisp_given = std::find(args.begin(), args.end(), "--ndisp") != args.end();
  // The camera's own scene is projector-lit: the active preset unless one is named.
  if (std::find(args.begin(), args.end(), "--preset") == args.end()) apply_stereo_preset("active", settings.stereo);
  consume_stereo_params(args, settings.stereo);
  settings.backend = take_backend_options(args);
  settings.templates = take_option(args, "--templates");
  settings.cad = take_option(args, "--cad");
  settings.model = resolve_detector_model_path(take_option(args, "--model"));
  take_namer_options(args, settings);
  const double score = take_number_option(args, "--score", kPickDetectionScore);
  const std::string threads = take_option(args, "--threads");
  const std::string tile = take_option(args, "--tile");
  const bool parts_given = std::find(args.begin(), args.end(), "--parts") != args.end();
  const std::string parts = take_option(args, "--parts");
  const std::string classes = take_option(args, "--classes-per-box");
  const std::string downscale = take_option(args, "--stereo-downscale");
  const std::string plan = take_option(args, "--stereo-plan");
  const std::string refine_boxes = take_option(args, "--refine-boxes");
  const std::string detect_in = take_option(args, "--detect-in");
  const std::string half_turns = take_option(args, "--half-turns");
  const std::string edges = take_option(args, "--edges");
  if (!edges.empty()) settings.pose.dcd.thresholds = edge_thresholds_named(edges, "--edges");
  const std::string depth_proposals = take_option(args, "--depth-proposals");
  const double retry_below = take_number_option(args, "--retry-below", settings.pose.retry_below_score);
  settings.quiet = take_flag(args, "--quiet");
  if (!(score >= 0.0 && score <= 1.0)) throw InputError("option --score", "must lie in [0, 1]");
  settings.detector.score_threshold = static_cast<float>(score);
  if (!threads.empty()) settings.threads = static_cast<int>(parse_whole_number("--threads", threads, 1, 1024));
  if (!classes.empty()) {
    settings.classes_per_box = static_cast<int>(parse_whole_number("--classes-per-box", classes, 1, 100));
  }
  if (!downscale.empty()) {
    settings.stereo_downscale = static_cast<int>(parse_whole_number("--stereo-downscale", downscale, 1, 8));
  }
  if (!plan.empty() && !parse_stereo_plan(plan, settings.stereo_plan)) {
    throw InputError("option --stereo-plan", "must be full or roi, not '" + plan + "'");
  }
  if (!refine_boxes.empty()) {
    if (refine_boxes != "on" && refine_boxes != "off") throw InputError("option --refine-boxes", "must be on or off");
    settings.refine_boxes = refine_boxes == "on";
  }
  if (!detect_in.empty()) {
    if (detect_in != "image" && detect_in != "bin") throw InputError("option --detect-in", "must be image or bin");
    settings.detect_in_bin = detect_in == "bin";
  }
  if (!half_turns.empty()) {
    if (half_turns != "on" && half_turns != "off") throw InputError("option --half-turns", "must be on or off");
    settings.pose.try_half_turns = half_turns == "on";
  }
  if (!depth_proposals.empty()) {
    if (depth_proposals != "on" && depth_proposals != "off") throw InputError("option --depth-proposals", "must be on or off");
    settings.depth_proposals = depth_proposals == "on";
  }
  if (!(retry_below >= 0.0 && retry_below <= 1.0)) throw InputError("option --retry-below", "must lie in [0, 1]");
  settings.pose.retry_below_score = retry_below;
  if (tile == "off") {
    settings.detection_tile = 0;
  } else if (!tile.empty() && tile != "auto") {
    settings.detection_tile = static_cast<int>(parse_whole_number("--tile", tile, 64, 8192));
  }
  if (parts_given) settings.detector.parts = parse_known_parts(parts);
  if (settings.templates.empty()) {
    throw InputError("option --templates", "missing (make them once with flexsight pose-templates CAD_DIR -o FILE)");
  }
  if (settings.cad.empty()) settings.cad = default_cad_dir();
  return options;
}

void take_pick_mode_options(std::vector<std::string>& args, PickSettings& settings) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    // A flag: "--all=x", or a word after it that names no input, is a value given to it.
    const bool inline_value = args[i].rfind("--all=", 0) == 0;
    const bool next_is_value = args[i] == "--all" && i + 1 < args.size() && args[i + 1].rfind("-", 0) != 0 &&
                               !std::filesystem::exists(args[i + 1]);
    if (inline_value || next_is_value) {
      throw InputError("option --all", "takes no value, got '" + (inline_value ? args[i].substr(6) : args[i + 1]) + "'");
    }
  }
  const bool all = take_flag(args, "--all");
  const std::string budget = take_option(args, "--budget-ms");
  if (all && !budget.empty()) throw InputError("option --budget-ms", "cannot be given with --all (which poses everything)");
  if (all) settings.mode = PickMode::All;
  if (!budget.empty()) {
    settings.mode = PickMode::Budget;
    settings.budget_ms = static_cast<int>(parse_whole_number("--budget-ms", budget, 0, 3600000));
  }
}

std::string pick_mode_options_help() {
  return "  --all              pose every proposal and rank them all (default: answer at the\n"
         "                     first candidate, in cheap order, whose pose passes the\n"
         "                     acceptance rule; docs/pick.md, \"The first pick first\")\n"
         "  --budget-ms N      after the first pick, go on posing in cheap order until N ms\n"
         "                     of the pick (stereo included) have passed, then rank what was\n"
         "                     posed (0..3600000)\n";
}

std::string pick_options_help() {
  std::ostringstream help;
  help << "  --templates T      the parts' edge templates (flexsight pose-templates CAD_DIR -o T)\n"
          "  --cad DIR          the CAD models the templates were made from (default:\n"
          "                     "
       << default_cad_dir() << ")\n"
       << "  --model M.onnx     the detector (default: the shipped one, " << default_detector_model_path() << ")\n"
       << "  --tile auto|off|N  detect in tiles: auto (default) sizes them so a part spans\n"
          "                     about 0.29 of a tile, as in the detector's training images,\n"
          "                     from the parts' diameters and the measured depth; off: the\n"
          "                     whole image; N: tiles of N pixels (64..8192)\n"
          "  --parts IDS        known-part mode: the parts this cell handles, object ids\n"
          "                     separated by commas (e.g. 5,12); only their classes are\n"
          "                     detected (the softmax over them and the background) and\n"
          "                     posed (default: every class of the detector)\n"
          "  --score S          detections scoring above S are posed (default 0.03: the\n"
          "                     detector proposes, the pose's fit decides)\n"
          "  --classes-per-box K  the detector's K best classes at a box are each posed, the\n"
          "                     best fit kept (default 5; 1: the detector decides alone)\n"
       << namer_options_help()
       << "  --stereo-downscale N  match the pair at 1/N of its size (1..8, default 1):\n"
          "                     the matcher's time falls with N squared; detection and\n"
          "                     pose keep the full image\n"
          "  --stereo-plan roi|full  what is matched: the bin alone over its disparity\n"
          "                     range, found in a match at 1/8 size (roi, default; the\n"
          "                     rest keeps that coarse match), or the whole pair (full);\n"
          "                     --stereo-downscale applies to what is matched\n"
          "  --detect-in image|bin  detection tiles over the whole image (default) or,\n"
          "                     with --stereo-plan roi, over the bin found alone\n"
          "  --refine-boxes on|off  with --stereo-downscale above 1, match each candidate's\n"
          "                     box again at full size before it is posed (default on)\n"
          "  --edges E          pose edge thresholds: contrast+noise (default: each box's\n"
          "                     grey levels stretched, thresholds above its noise),\n"
          "                     fixed, contrast or noise (docs/pose.md)\n"
          "  --half-turns on|off  also fit each candidate pose turned 180 degrees about\n"
          "                     the part's axes (default on; off: a quarter of the ICP runs)\n"
          "  --retry-below S    when the best candidates of a box score below S, fit every\n"
          "                     other candidate too (default 0.5; 0: never)\n"
          "  --depth-proposals on|off  also pose the parts segmented from the depth above\n"
          "                     the bin floor that no detector box matches (default off)\n"
          "  --threads N        parts posed at once (default: all cores)\n"
          "  --quiet            no progress lines\n"
          "  --ndisp N and the stereo parameters of flexsight stereo; --preset active (for\n"
          "                     projector-lit pairs) unless another --preset is given\n"
       << backend_options_help();
  return help.str();
}

int pick_ndisp(const PickOptions& options, const std::string& calib) {
  if (options.ndisp_given) return options.settings.stereo.ndisp;
  try {
    return read_middlebury_calib(calib).ndisp;
  } catch (const InputError& e) {
    // The reason travels along: a Middlebury file may be unreadable for another cause
    // (e.g. its projector pattern is missing), which the user must see.
    throw InputError("option --ndisp", "missing: " + calib + " gives no disparity range (" + e.what() + ")");
  }
}

}  // namespace flexsight

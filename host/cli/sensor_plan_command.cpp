// flexsight sensor-plan: where the cameras and the projector of a FlexSight-C1-like
// sensor see a working volume, the depth resolution and disparity range there, and the
// conditions of the paper's 0.3 mm (host/sensor/; docs/sensor-plan.md). Defaults are the
// paper's camera.
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "host/cli/arguments.h"
#include "host/cli/commands.h"
#include "host/dataset/dataset_files.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/staged_folder.h"
#include "host/sensor/plan_drawing.h"
#include "host/sensor/plan_report.h"
#include "host/sensor/sensor_plan.h"

namespace flexsight {
namespace {

// The coverage grid's sample count above which --grid is refused (a few seconds' work).
constexpr long long kMaxSamples = 200'000'000LL;

void print_help() {
  std::cout
      << "usage: flexsight sensor-plan [options] [-o DIR]\n"
         "Coverage of a working volume by two rectified cameras and a projector, depth\n"
         "resolution, disparity range, and top/side pictures. Defaults: the paper's FlexSight C1.\n"
         "  --baseline MM         camera centres apart (default 500)\n"
         "  --distance MM         the volume's centroid from the baseline (default 1250)\n"
         "  --focal PX            focal length in pixels (default: the largest at which the\n"
         "                        volume fits both images)\n"
         "  --hfov DEG            or the cameras' horizontal field of view, in (0, 180)\n"
         "  --size WxH            image size (default 4000x3000, 12 MP)\n"
         "  --pixel-um UM         pixel pitch, for focal lengths in mm (default 1.55)\n"
         "  --doffs PX|auto       cx(right) - cx(left), Middlebury's doffs (default auto: the\n"
         "                        volume centred in both images)\n"
         "  --projector-fov HxV   projector field of view in degrees (default 35x35)\n"
         "  --projector-offset MM projector x from the middle of the baseline (default 0;\n"
         "                        within the baseline)\n"
         "  --volume WxHxD        working volume in mm: across the baseline, vertical, depth\n"
         "                        (default 600x400x400)\n"
         "  --subpixel STEP       the matcher's disparity step in px, e.g. 0.25 or 1/16\n"
         "                        (default 1/16: OpenCV SGBM/BM's 4-bit sub-pixel)\n"
         "  --target-dz MM        depth step to explain at the far plane (default 0.3, the paper's)\n"
         "  --grid MM             coverage sampling step (default 10)\n"
         "  -o DIR                write report.md, report.json, top.png, side.png (whole or nothing)\n"
         "  --overwrite           replace DIR if it exists\n";
}

// A positive, finite number option (`fallback` when absent).
double positive_option(std::vector<std::string>& args, const std::string& name, double fallback) {
  const double value = take_number_option(args, name, fallback);
  if (!(value > 0.0)) throw InputError("option " + name, "expected a positive number");
  return value;
}

// One field of an "AxB[xC]" value, read by the project's number parser so that its
// messages name the option like every other number.
double number_field(const std::string& name, const std::string& text) {
  std::vector<std::string> one{name, text};
  return take_number_option(one, name, 0.0);
}

std::vector<std::string> split_x(const std::string& name, const std::string& text, size_t fields,
                                 const std::string& form) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t end = text.find('x', start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  if (parts.size() != fields) throw InputError("option " + name, "expected " + form + ", got '" + text + "'");
  for (const std::string& p : parts) {
    if (p.empty()) throw InputError("option " + name, "expected " + form + ", got '" + text + "'");
  }
  return parts;
}

double angle_field(const std::string& name, const std::string& text) {
  const double degrees = number_field(name, text);
  if (!(degrees > 0.0 && degrees < 180.0)) {
    throw InputError("option " + name, "expected an angle in (0, 180) degrees, got '" + text + "'");
  }
  return degrees;
}

// "0.25" or "1/16".
double parse_subpixel(const std::string& text) {
  const std::string name = "--subpixel";
  double value = 0.0;
  const size_t slash = text.find('/');
  if (slash == std::string::npos) {
    value = number_field(name, text);
  } else {
    const auto num = parse_whole_number(name, text.substr(0, slash), 1, 1'000'000);
    const auto den = parse_whole_number(name, text.substr(slash + 1), 1, 1'000'000);
    value = static_cast<double>(num) / static_cast<double>(den);
  }
  if (!(value > 0.0 && value <= 100.0)) {
    throw InputError("option " + name, "expected a disparity step in (0, 100] px, got '" + text + "'");
  }
  return value;
}

SensorPlanInputs parse_inputs(std::vector<std::string>& args) {
  SensorPlanInputs in;
  in.baseline_mm = positive_option(args, "--baseline", in.baseline_mm);
  in.volume.distance = positive_option(args, "--distance", in.volume.distance);

  const std::string size = take_option(args, "--size");
  if (!size.empty()) {
    const auto parts = split_x("--size", size, 2, "WxH in pixels");
    in.width = static_cast<int>(parse_whole_number("--size", parts[0], 1, 100000));
    in.height = static_cast<int>(parse_whole_number("--size", parts[1], 1, 100000));
  }
  in.pixel_um = positive_option(args, "--pixel-um", in.pixel_um);

  const std::string focal = take_option(args, "--focal");
  const std::string hfov = take_option(args, "--hfov");
  if (!focal.empty() && !hfov.empty()) throw InputError("option --focal", "give --focal or --hfov, not both");
  if (!focal.empty()) {
    in.focal_px = number_field("--focal", focal);
    if (!(*in.focal_px > 0.0)) throw InputError("option --focal", "expected a positive focal length in px");
  }
  if (!hfov.empty()) in.focal_px = focal_from_hfov(angle_field("--hfov", hfov), in.width);

  const std::string doffs = take_option(args, "--doffs");
  if (!doffs.empty() && doffs != "auto") in.doffs_px = number_field("--doffs", doffs);

  const std::string projector_fov = take_option(args, "--projector-fov");
  if (!projector_fov.empty()) {
    const auto parts = split_x("--projector-fov", projector_fov, 2, "HxV in degrees");
    in.projector_hfov_deg = angle_field("--projector-fov", parts[0]);
    in.projector_vfov_deg = angle_field("--projector-fov", parts[1]);
  }
  in.projector_offset_mm = take_number_option(args, "--projector-offset", 0.0);
  if (std::abs(in.projector_offset_mm) > in.baseline_mm / 2.0) {
    throw InputError("option --projector-offset", "the projector must sit on the baseline, within +-" +
                                                      std::to_string(in.baseline_mm / 2.0) + " mm of its middle");
  }

  const std::string volume = take_option(args, "--volume");
  if (!volume.empty()) {
    const auto parts = split_x("--volume", volume, 3, "WxHxD in mm");
    double* fields[3] = {&in.volume.width, &in.volume.height, &in.volume.depth};
    for (int i = 0; i < 3; ++i) {
      *fields[i] = number_field("--volume", parts[i]);
      if (!(*fields[i] > 0.0)) throw InputError("option --volume", "expected positive sizes, got '" + volume + "'");
    }
  }
  if (!(in.volume.near_z() > 0.0)) {
    throw InputError("option --distance", "the volume must lie in front of the sensor: distance > depth / 2 (" +
                                              std::to_string(in.volume.depth / 2.0) + " mm)");
  }

  const std::string subpixel = take_option(args, "--subpixel");
  if (!subpixel.empty()) in.subpixel_px = parse_subpixel(subpixel);
  in.target_dz_mm = positive_option(args, "--target-dz", in.target_dz_mm);
  in.grid_mm = positive_option(args, "--grid", in.grid_mm);
  const double samples = static_cast<double>(cells_along(in.volume.width, in.grid_mm)) *
                         static_cast<double>(cells_along(in.volume.height, in.grid_mm)) *
                         static_cast<double>(cells_along(in.volume.depth, in.grid_mm));
  if (samples > static_cast<double>(kMaxSamples)) {
    throw InputError("option --grid", "too fine for this volume: " + std::to_string(static_cast<long long>(samples)) +
                                          " samples (at most " + std::to_string(kMaxSamples) + ")");
  }
  return in;
}

void write_picture(const std::string& path, const cv::Mat& bgr) {
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  write_image(path, rgb);
}

}  // namespace

int run_sensor_plan_command(std::vector<std::string> args) {
  // No arguments is a valid run (the paper's camera), so only --help prints the usage.
  if (take_flag(args, "--help") || take_flag(args, "-h")) {
    print_help();
    return 0;
  }
  const std::string output = take_option(args, "-o");
  const bool overwrite = take_flag(args, "--overwrite");
  SensorPlanInputs inputs = parse_inputs(args);
  reject_unknown_options(args);
  if (!args.empty()) throw InputError("sensor-plan", "unexpected argument '" + args[0] + "' (all inputs are options)");

  // The output folder is checked (and its staging folder made) before the plan is computed.
  std::optional<StagedFolder> staged;
  if (!output.empty()) staged.emplace(output, overwrite, "-o");
  const SensorPlan plan = make_sensor_plan(inputs);
  // A volume partly outside the views is what the report is for; one entirely outside
  // means the options are wrong.
  if (plan.coverage.volume.all <= 0.0) {
    throw InputError("working volume (--volume, --distance)",
                     "no part of it is seen by both cameras and the projector; check --focal/--hfov, "
                     "--doffs, --baseline and --projector-fov");
  }
  if (staged) {
    dataset_files::write_text(staged->path() + "/report.md", plan_markdown(plan));
    dataset_files::write_text(staged->path() + "/report.json", plan_json(plan));
    write_picture(staged->path() + "/top.png", draw_top_view(plan.rig, inputs.volume, plan.coverage));
    write_picture(staged->path() + "/side.png", draw_side_view(plan.rig, inputs.volume, plan.coverage));
    staged->commit();
  }
  std::cout << plan_table(plan);
  if (!output.empty()) std::cout << "written: " << output << "/{report.md, report.json, top.png, side.png}\n";
  return 0;
}

}  // namespace flexsight

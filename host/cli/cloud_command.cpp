// flexsight cloud: a disparity map (PFM) and its left image to depth and a colored
// point cloud, for results computed earlier or by another matcher.
#include <iostream>

#include "host/cli/arguments.h"
#include "host/cli/cloud_outputs.h"
#include "host/cli/commands.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/output_path.h"
#include "host/io/pfm.h"

namespace flexsight {
namespace {

void print_help() {
  std::cout << "usage: flexsight cloud DISP.pfm LEFT --calib FILE -o CLOUD.ply [options]\n"
               "  -o CLOUD.ply                the point cloud (same as --ply)\n"
               "  --planes PLANES.pfm         per-pixel planes (a, b, c) from 'stereo --planes':\n"
               "                              exact normals; otherwise from the disparity slope\n"
               "  --conf CONF.pfm             per-pixel confidence from 'stereo --conf'\n"
            << cloud_output_options_help();
}

// A PFM that must match the disparity's size and have `channels` channels.
cv::Mat read_companion(const std::string& path, const cv::Mat& disparity, int channels) {
  if (path.empty()) return {};
  cv::Mat image = read_pfm(path);
  if (image.size() != disparity.size() || image.channels() != channels) {
    throw InputError(path, "is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                               " with " + std::to_string(image.channels()) +
                               " channel(s); expected " + std::to_string(disparity.cols) + "x" +
                               std::to_string(disparity.rows) + " with " +
                               std::to_string(channels));
  }
  return image;
}

}  // namespace

int run_cloud_command(std::vector<std::string> args) {
  if (const std::optional<int> code = usage_exit_code(args, print_help)) return *code;
  std::string output = take_option(args, "-o");
  const std::string planes_path = take_option(args, "--planes");
  const std::string conf_path = take_option(args, "--conf");
  CloudOutputOptions options = take_cloud_output_options(args);
  reject_unknown_options(args);
  if (!output.empty()) options.ply = output;
  if (args.size() != 2) {
    throw InputError("cloud", "expected DISP.pfm LEFT, got " + std::to_string(args.size()) +
                                  " inputs");
  }
  if (!options.wants_3d()) throw InputError("option -o", "an output PLY path is required");
  for (const std::string& path : {options.ply, options.depth, options.render}) check_output_file(path);
  const cv::Mat disparity = read_pfm(args[0]);
  if (disparity.channels() != 1) throw InputError(args[0], "is not a one-channel disparity map");
  const cv::Mat left = load_rgb8(args[1]);
  if (left.size() != disparity.size()) {
    throw InputError(args[1], "is " + std::to_string(left.cols) + "x" + std::to_string(left.rows) +
                                  ", the disparity " + std::to_string(disparity.cols) + "x" +
                                  std::to_string(disparity.rows));
  }
  const cv::Mat planes = read_companion(planes_path, disparity, 3);
  const cv::Mat confidence = read_companion(conf_path, disparity, 1);
  write_cloud_outputs(options, disparity, left, planes, confidence);
  return 0;
}

}  // namespace flexsight

#pragma once
// The 3D outputs that `stereo` and `cloud` share: options, and writing depth, point
// cloud and its picture from a disparity map.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/geometry/point_cloud.h"
#include "host/geometry/ply.h"

namespace flexsight {

struct CloudOutputOptions {
  std::string ply;          // --ply CLOUD.ply
  PlyFormat ply_format = PlyFormat::binary_little_endian;  // --ply-ascii
  std::string calib;        // --calib FILE
  std::string depth;        // --depth DEPTH.pfm
  std::string depth_unit = "mm";  // --depth-unit mm|m
  std::string render;       // --render VIEW.png
  CloudFilter filter;       // --min-confidence, --min-depth, --max-depth

  bool wants_3d() const { return !ply.empty() || !depth.empty() || !render.empty(); }
};

// Takes the options above out of `args`. Throws InputError for malformed values
// (a negative depth bound, min above max, a confidence outside [0, 1], an unknown unit).
CloudOutputOptions take_cloud_output_options(std::vector<std::string>& args);

// Help lines of those options.
std::string cloud_output_options_help();

// Reads the calibration (and checks it fits a width x height image) so that a bad
// --calib fails before a long run rather than after it. No-op without 3D outputs.
void check_cloud_outputs(const CloudOutputOptions& options, int width, int height);

// Writes what `options` asks for. `left_rgb` CV_8UC3 RGB; `planes` and `confidence`
// may be empty. The camera is read from options.calib and resized to the image.
// Prints one line per file written.
void write_cloud_outputs(const CloudOutputOptions& options, const cv::Mat& disparity,
                         const cv::Mat& left_rgb, const cv::Mat& planes,
                         const cv::Mat& confidence);

}  // namespace flexsight

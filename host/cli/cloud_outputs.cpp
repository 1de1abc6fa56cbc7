#include "host/cli/cloud_outputs.h"

#include <chrono>
#include <cstdio>

#include "host/cli/arguments.h"
#include "host/geometry/cloud_render.h"
#include "host/geometry/depth_from_disparity.h"
#include "host/geometry/stereo_camera.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/pfm.h"

namespace flexsight {

CloudOutputOptions take_cloud_output_options(std::vector<std::string>& args) {
  CloudOutputOptions options;
  options.ply = take_option(args, "--ply");
  if (take_flag(args, "--ply-ascii")) options.ply_format = PlyFormat::ascii;
  options.calib = take_option(args, "--calib");
  options.depth = take_option(args, "--depth");
  const std::string unit = take_option(args, "--depth-unit");
  if (!unit.empty()) options.depth_unit = unit;
  if (options.depth_unit != "mm" && options.depth_unit != "m") {
    throw InputError("option --depth-unit", "expected mm or m, got '" + options.depth_unit + "'");
  }
  options.render = take_option(args, "--render");
  CloudFilter& filter = options.filter;
  filter.min_confidence = static_cast<float>(take_number_option(args, "--min-confidence", 0.0));
  filter.min_depth = take_number_option(args, "--min-depth", 0.0);
  filter.max_depth = take_number_option(args, "--max-depth", 0.0);
  if (!(filter.min_confidence >= 0 && filter.min_confidence <= 1)) {
    throw InputError("option --min-confidence", "must lie in [0, 1]");
  }
  if (filter.min_depth < 0 || filter.max_depth < 0) {
    throw InputError("option --min-depth/--max-depth", "depth bounds must not be negative");
  }
  if (filter.max_depth > 0 && filter.min_depth >= filter.max_depth) {
    throw InputError("option --min-depth", "must be below --max-depth");
  }
  return options;
}

std::string cloud_output_options_help() {
  return "3D outputs (need --calib: Middlebury calib.txt, KITTI calib, or OpenCV YAML/XML with Q):\n"
         "  --calib FILE                camera calibration (a scene folder's calib.txt by default)\n"
         "  --ply CLOUD.ply             colored point cloud with normals and confidence\n"
         "  --ply-ascii                 ASCII PLY instead of binary little-endian\n"
         "  --depth DEPTH.pfm           depth map (Z, NaN where unmatched)\n"
         "  --depth-unit mm|m           unit of --depth (default mm)\n"
         "  --render VIEW.png           picture of the cloud from beside the camera\n"
         "  --min-confidence C          keep points with confidence >= C (0..1)\n"
         "  --min-depth Z, --max-depth Z  keep points in this depth range (calibration unit)\n";
}

namespace {

// The camera of --calib, sized to the images; throws InputError when it is missing or bad.
StereoCamera sized_camera(const CloudOutputOptions& options, int width, int height) {
  if (options.calib.empty()) {
    throw InputError("option --calib", "a calibration file is needed for --ply/--depth/--render");
  }
  return read_stereo_camera(options.calib).resized_to(width, height);
}

}  // namespace

void check_cloud_outputs(const CloudOutputOptions& options, int width, int height) {
  if (options.wants_3d()) sized_camera(options, width, height);
}

void write_cloud_outputs(const CloudOutputOptions& options, const cv::Mat& disparity,
                         const cv::Mat& left_rgb, const cv::Mat& planes,
                         const cv::Mat& confidence) {
  if (!options.wants_3d()) return;
  const auto start = std::chrono::steady_clock::now();
  const StereoCamera camera = sized_camera(options, disparity.cols, disparity.rows);
  if (!options.depth.empty()) {
    const double metres = options.depth_unit == "m" ? 1.0 : 1e-3;
    write_pfm(options.depth, depth_from_disparity(disparity, camera, metres, DepthRule::cloud()));
    std::printf("wrote %s (depth in %s)\n", options.depth.c_str(), options.depth_unit.c_str());
  }
  if (options.ply.empty() && options.render.empty()) return;
  if (options.filter.min_confidence > 0 && confidence.empty()) {
    throw InputError("option --min-confidence",
                     "needs a confidence map ('stereo' makes one with PatchMatch; 'cloud' "
                     "takes one with --conf)");
  }
  const PointCloud cloud =
      build_point_cloud(disparity, left_rgb, planes, confidence, camera, options.filter);
  if (!options.ply.empty()) {
    write_ply(options.ply, cloud, options.ply_format);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("wrote %s (%zu points in %s, %.3f s)\n", options.ply.c_str(), cloud.size(),
                cloud.unit.c_str(), seconds);
  }
  if (!options.render.empty()) {
    write_image(options.render, render_point_cloud(cloud));
    std::printf("wrote %s\n", options.render.c_str());
  }
}

}  // namespace flexsight

// flexsight render: a picture of CAD parts, to look at a mesh and at the renderer's
// shading. The parts stand side by side, turned alike, in front of a floor facing the
// camera, as in a bin seen from above.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "host/cli/arguments.h"
#include "host/cli/commands.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/pfm.h"
#include "host/render/mesh.h"
#include "host/render/raycaster.h"
#include "host/render/shading.h"

namespace flexsight {
namespace {

void print_help() {
  std::cout
      << "usage: flexsight render MESH [MESH ...] -o IMAGE.png [options]\n"
         "  MESH                  STL, PLY or OBJ in mm; several stand side by side\n"
         "  -o IMAGE.png          the shaded picture (8-bit RGB)\n"
         "  --depth DEPTH.pfm     depth in mm (0 where no surface)\n"
         "  --mask MASK.png       8-bit: part i as i + 1, floor and background 0\n"
         "  --size WxH            image size (default 640x480)\n"
         "  --focal F             focal length in pixels (default: the image width);\n"
         "                        principal point at the image centre\n"
         "  --distance MM         distance of the parts from the camera (default: the row\n"
         "                        of parts fills about 60 % of the image width)\n"
         "  --rotation RX,RY,RZ   the parts' turn in degrees about the camera's x, y, z\n"
         "                        axes, in that order (default 30,-40,0)\n"
         "  --no-floor            no floor behind the parts\n"
         "  --light-radius MM     radius of the light: soft shadows (default 0: hard)\n"
         "  --shadow-samples N    shadow rays per pixel for a light with a radius (default 8)\n"
         "  --camera-light        a second light at the camera\n"
         "  --seed S              key of the shadow jitter and the parts' tints (default 1)\n"
         "  --threads N           OpenMP threads (default: all)\n";
}

std::vector<double> parse_numbers(const std::string& option, const std::string& text,
                                  char separator, size_t count) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, separator)) {
    try {
      size_t used = 0;
      values.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(values.back())) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InputError("option " + option, "expected " + std::to_string(count) +
                                               " numbers separated by '" + separator + "', got '" +
                                               text + "'");
    }
  }
  if (values.size() != count) {
    throw InputError("option " + option, "expected " + std::to_string(count) +
                                             " numbers separated by '" + separator + "', got '" +
                                             text + "'");
  }
  return values;
}

int positive_int(const std::string& option, double value) {
  if (!(value >= 1.0 && value <= 1e6) || value != std::floor(value)) {
    throw InputError("option " + option, "expected a positive whole number");
  }
  return static_cast<int>(value);
}

}  // namespace

int run_render_command(std::vector<std::string> args) {
  // --help asks for the usage (exit 0); no arguments at all is a usage error (exit 1).
  const bool help = take_flag(args, "--help") || take_flag(args, "-h");
  if (help || args.empty()) {
    print_help();
    return help ? 0 : 1;
  }
  const std::string output = take_option(args, "-o");
  const std::string depth_path = take_option(args, "--depth");
  const std::string mask_path = take_option(args, "--mask");
  const std::string size_text = take_option(args, "--size");
  const double focal_option = take_number_option(args, "--focal", 0.0);
  const double distance_option = take_number_option(args, "--distance", 0.0);
  const std::string rotation_text = take_option(args, "--rotation");
  const bool floor = !take_flag(args, "--no-floor");
  ShadingOptions shading;
  const double light_radius = take_number_option(args, "--light-radius", 0.0);
  if (light_radius < 0.0) throw InputError("option --light-radius", "must be 0 or more");
  shading.lights[0].radius = static_cast<float>(light_radius);
  shading.shadow_samples =
      positive_int("--shadow-samples", take_number_option(args, "--shadow-samples", 8));
  shading.camera_light = take_flag(args, "--camera-light");
  const double seed = take_number_option(args, "--seed", 1);
  const double threads = take_number_option(args, "--threads", 0);
  reject_unknown_options(args);

  if (args.empty()) throw InputError("render", "expected at least one MESH");
  if (args.size() > 254) throw InputError("render", "at most 254 meshes (the mask is 8-bit)");
  if (output.empty()) throw InputError("option -o", "an output picture path is required");
  if (!(seed >= 0 && seed <= 4294967295.0) || seed != std::floor(seed)) {
    throw InputError("option --seed", "expected a whole number in 0..4294967295");
  }
  shading.seed = static_cast<std::uint32_t>(seed);
  if (!(threads >= 0 && threads <= 4096) || threads != std::floor(threads)) {
    throw InputError("option --threads", "expected a whole number >= 0");
  }
  shading.threads = static_cast<int>(threads);
  PinholeCamera camera;
  if (!size_text.empty()) {
    const std::vector<double> size = parse_numbers("--size", size_text, 'x', 2);
    camera.width = positive_int("--size", size[0]);
    camera.height = positive_int("--size", size[1]);
  }
  camera.fx = camera.fy = focal_option != 0.0 ? focal_option : camera.width;
  camera.cx = (camera.width - 1) / 2.0;
  camera.cy = (camera.height - 1) / 2.0;
  camera.check();
  if (distance_option < 0.0) throw InputError("option --distance", "must be positive");
  const std::vector<double> degrees = rotation_text.empty()
                                          ? std::vector<double>{30, -40, 0}
                                          : parse_numbers("--rotation", rotation_text, ',', 3);
  shading.check();
  // Every output's folder is checked before the meshes are read.
  for (const std::string& path : {output, depth_path, mask_path}) {
    if (path.empty()) continue;
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder)) {
      throw InputError(path, "cannot be written: its folder does not exist");
    }
  }

  std::vector<std::shared_ptr<const Mesh>> meshes;
  float spacing = 0.0f;
  for (const std::string& path : args) {
    meshes.push_back(std::make_shared<const Mesh>(load_mesh(path)));
    spacing = std::max(spacing, 1.1f * meshes.back()->diameter);
  }
  const double row = spacing * meshes.size();
  const double distance =
      distance_option > 0.0 ? distance_option : camera.fx * row / (0.6 * camera.width);
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(degrees[2] * M_PI / 180.0, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(degrees[1] * M_PI / 180.0, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(degrees[0] * M_PI / 180.0, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();

  RenderScene scene;
  for (size_t i = 0; i < meshes.size(); ++i) {
    Pose pose;
    pose.R = R;
    // The part's box centre on the row, the row centred on the optical axis.
    const Eigen::Vector3d slot((i + 0.5) * spacing - row / 2.0, 0.0, distance);
    pose.t = slot - R * meshes[i]->bounds.center().cast<double>();
    Material material;
    material.albedo = tinted_grey(shading.seed, static_cast<int>(i));
    scene.add_instance(scene.add_mesh(meshes[i]), pose, material);
  }
  if (floor) {
    // A matte floor just behind the deepest part, wide enough to fill the view.
    const double floor_z = distance + spacing / 2.0;
    const float half =
        static_cast<float>(floor_z * std::max(camera.width / camera.fx, camera.height / camera.fy));
    auto square = std::make_shared<const Mesh>(
        make_mesh("floor", {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}},
                  {{0, 1, 2}, {0, 2, 3}}));
    Pose pose;
    pose.t = {0.0, 0.0, floor_z};
    Material material;
    material.albedo = {0.35f, 0.35f, 0.37f};
    material.specular = 0.05f;
    scene.add_instance(scene.add_mesh(square), pose, material);
  }
  scene.commit();
  // The light above and to the left of the camera, a distance's height above the parts.
  shading.lights[0].position = {static_cast<float>(-0.4 * distance),
                                static_cast<float>(-0.8 * distance), 0.0f};

  RaycastOptions raycast_options;
  raycast_options.threads = shading.threads;
  const RaycastImages images = raycast(scene, camera, raycast_options);
  write_image(output, shade(scene, images, shading));
  if (!depth_path.empty()) write_pfm(depth_path, images.depth);
  if (!mask_path.empty()) {
    cv::Mat mask(images.instance.size(), CV_8UC1);
    for (int y = 0; y < mask.rows; ++y) {
      for (int x = 0; x < mask.cols; ++x) {
        const int id = images.instance.at<std::int32_t>(y, x);
        mask.at<std::uint8_t>(y, x) =
            id >= 0 && id < static_cast<int>(meshes.size()) ? std::uint8_t(id + 1) : 0;
      }
    }
    write_image(mask_path, mask);
  }
  std::cerr << "rendered " << meshes.size() << " part(s) at " << distance << " mm, " << camera.width
            << "x" << camera.height << "\n";
  return 0;
}

}  // namespace flexsight

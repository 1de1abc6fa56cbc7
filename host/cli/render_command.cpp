// flexsight render: a picture of CAD parts, to look at a mesh and at the renderer's
// shading (the scene: host/render/part_row.h).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "host/cli/arguments.h"
#include "host/cli/commands.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/output_path.h"
#include "host/io/pfm.h"
#include "host/render/mesh.h"
#include "host/render/part_row.h"
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

struct RenderOptions {
  std::string output, depth_path, mask_path;
  std::vector<std::string> meshes;
  PinholeCamera camera;
  PartRowLayout layout;
  ShadingOptions shading;
};

// --light-radius, --shadow-samples and --camera-light.
ShadingOptions take_shading_options(std::vector<std::string>& args) {
  ShadingOptions shading;
  const double light_radius = take_number_option(args, "--light-radius", 0.0);
  if (light_radius < 0.0) throw InputError("option --light-radius", "must be 0 or more");
  shading.lights[0].radius = static_cast<float>(light_radius);
  shading.shadow_samples =
      positive_int("--shadow-samples", take_number_option(args, "--shadow-samples", 8));
  shading.camera_light = take_flag(args, "--camera-light");
  return shading;
}

// --seed and --threads' values, checked.
void set_seed_and_threads(ShadingOptions& shading, double seed, double threads) {
  if (!(seed >= 0 && seed <= 4294967295.0) || seed != std::floor(seed)) {
    throw InputError("option --seed", "expected a whole number in 0..4294967295");
  }
  shading.seed = static_cast<std::uint32_t>(seed);
  if (!(threads >= 0 && threads <= 4096) || threads != std::floor(threads)) {
    throw InputError("option --threads", "expected a whole number >= 0");
  }
  shading.threads = static_cast<int>(threads);
}

constexpr int kMaxImageSide = 16384;

// --size and --focal: the principal point at the image centre.
PinholeCamera camera_of_options(const std::string& size_text, double focal_option) {
  PinholeCamera camera;
  if (!size_text.empty()) {
    const std::vector<double> size = parse_numbers("--size", size_text, 'x', 2);
    // The synth commands' bound: larger pictures would only fail in the allocation.
    for (const double side : size) {
      if (!(side >= 1.0 && side <= kMaxImageSide) || side != std::floor(side)) {
        throw InputError("option --size", "expected WxH with 1 <= W, H <= " + std::to_string(kMaxImageSide) +
                                              ", got '" + size_text + "'");
      }
    }
    camera.width = static_cast<int>(size[0]);
    camera.height = static_cast<int>(size[1]);
  }
  camera.fx = camera.fy = focal_option != 0.0 ? focal_option : camera.width;
  camera.cx = (camera.width - 1) / 2.0;
  camera.cy = (camera.height - 1) / 2.0;
  camera.check();
  return camera;
}

RenderOptions parse_render_options(std::vector<std::string> args) {
  RenderOptions options;
  take_options(args, {{"-o", &options.output},
                      {"--depth", &options.depth_path},
                      {"--mask", &options.mask_path}});
  const std::string size_text = take_option(args, "--size");
  const double focal_option = take_number_option(args, "--focal", 0.0);
  options.layout.distance = take_number_option(args, "--distance", 0.0);
  const std::string rotation_text = take_option(args, "--rotation");
  options.layout.floor = !take_flag(args, "--no-floor");
  options.shading = take_shading_options(args);
  const double seed = take_number_option(args, "--seed", 1);
  const double threads = take_number_option(args, "--threads", 0);
  reject_unknown_options(args);

  if (args.empty()) throw InputError("render", "expected at least one MESH");
  if (args.size() > 254) throw InputError("render", "at most 254 meshes (the mask is 8-bit)");
  if (options.output.empty()) throw InputError("option -o", "an output picture path is required");
  set_seed_and_threads(options.shading, seed, threads);
  options.camera = camera_of_options(size_text, focal_option);
  if (options.layout.distance < 0.0) throw InputError("option --distance", "must be positive");
  if (!rotation_text.empty()) {
    const std::vector<double> degrees = parse_numbers("--rotation", rotation_text, ',', 3);
    options.layout.rotation_degrees = {degrees[0], degrees[1], degrees[2]};
  }
  options.shading.check();
  // Every output's folder is checked before the meshes are read.
  for (const std::string& path : {options.output, options.depth_path, options.mask_path}) check_output_file(path);
  options.meshes = args;
  return options;
}

}  // namespace

int run_render_command(std::vector<std::string> args) {
  // --help asks for the usage (exit 0); no arguments at all is a usage error (exit 1).
  const bool help = take_flag(args, "--help") || take_flag(args, "-h");
  if (help || args.empty()) {
    print_help();
    return help ? 0 : 1;
  }
  RenderOptions options = parse_render_options(std::move(args));
  std::vector<std::shared_ptr<const Mesh>> meshes;
  for (const std::string& path : options.meshes) meshes.push_back(std::make_shared<const Mesh>(load_mesh(path)));
  const PartRow row = compose_part_row(meshes, options.camera, options.layout, options.shading.seed);
  options.shading.lights[0].position = row.light;

  RaycastOptions raycast_options;
  raycast_options.threads = options.shading.threads;
  const RaycastImages images = raycast(row.scene, options.camera, raycast_options);
  write_image(options.output, shade(row.scene, images, options.shading));
  if (!options.depth_path.empty()) write_pfm(options.depth_path, images.depth);
  if (!options.mask_path.empty()) write_image(options.mask_path, part_mask(images.instance, static_cast<int>(meshes.size())));
  std::cerr << "rendered " << meshes.size() << " part(s) at " << row.distance << " mm, " << options.camera.width
            << "x" << options.camera.height << "\n";
  return 0;
}

}  // namespace flexsight

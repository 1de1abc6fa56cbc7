#include "host/sim/bin_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "host/dataset/gt_info.h"
#include "host/render/shading.h"
#include "host/sim/sensor_model.h"
#include "host/synth/camera_effects.h"
#include "host/synth/synth_random.h"

namespace flexsight {
namespace {

using synth_detail::SynthRandom;

// The random streams of one bin (synth_random.h): each purpose its own, so a change in
// one leaves the others' numbers as they were.
enum BinStream : std::uint32_t {
  kStreamCount = 0xB1, // how many parts, which ones
  kStreamDrop = 0xB2,  // where and how they fall
  kStreamLook = 0xB3,  // their albedos
  kStreamNoise = 0xB4, // + image: the sensor noise keys
};

// The table under the bin (mm): far wider than any view of the volume, so every pixel
// sees a surface.
constexpr double kTableSize = 4000.0;

void add_box(std::vector<Eigen::Vector3f>& positions, std::vector<std::array<std::uint32_t, 3>>& triangles,
             const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const auto base = static_cast<std::uint32_t>(positions.size());
  for (int i = 0; i < 8; ++i) {
    positions.emplace_back(float((i & 1) ? hi.x() : lo.x()), float((i & 2) ? hi.y() : lo.y()),
                           float((i & 4) ? hi.z() : lo.z()));
  }
  // Counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    triangles.push_back({base + q[0], base + q[1], base + q[2]});
    triangles.push_back({base + q[0], base + q[2], base + q[3]});
  }
}

Mesh make_bin_mesh(const BinGeometry& bin) {
  std::vector<Eigen::Vector3f> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  const double L = 0.5 * bin.length_mm, W = 0.5 * bin.width_mm, H = bin.wall_height_mm;
  const double T = bin.wall_thickness_mm, F = bin.floor_thickness_mm;
  add_box(positions, triangles, {-L - T, -W - T, -F}, {L + T, W + T, 0.0});
  add_box(positions, triangles, {-L - T, -W - T, 0.0}, {-L, W + T, H});
  add_box(positions, triangles, {L, -W - T, 0.0}, {L + T, W + T, H});
  add_box(positions, triangles, {-L, -W - T, 0.0}, {L, -W, H});
  add_box(positions, triangles, {-L, W, 0.0}, {L, W + T, H});
  return make_mesh("bin", positions, triangles);
}

Mesh make_table_mesh(const BinGeometry& bin) {
  std::vector<Eigen::Vector3f> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  const double h = 0.5 * kTableSize, z = -bin.floor_thickness_mm;
  add_box(positions, triangles, {-h, -h, z - 20.0}, {h, h, z});
  return make_mesh("table", positions, triangles);
}

// The same sRGB encoding as shade() (host/render/shading.h): clip to [0, 1], encode.
class Srgb8 {
 public:
  Srgb8() {
    for (int i = 0; i < kSize; ++i) {
      const double v = double(i) / (kSize - 1);
      const double s = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
      table_[i] = static_cast<std::uint8_t>(std::lround(255.0 * s));
    }
  }
  cv::Mat operator()(const cv::Mat& radiance) const {
    cv::Mat rgb(radiance.size(), CV_8UC3);
    for (int y = 0; y < radiance.rows; ++y) {
      const cv::Vec3f* src = radiance.ptr<cv::Vec3f>(y);
      cv::Vec3b* dst = rgb.ptr<cv::Vec3b>(y);
      for (int x = 0; x < radiance.cols; ++x) {
        for (int c = 0; c < 3; ++c) {
          const float clipped = std::min(std::max(src[x][c], 0.0f), 1.0f);
          dst[x][c] = table_[static_cast<int>(clipped * float(kSize - 1) + 0.5f)];
        }
      }
    }
    return rgb;
  }

 private:
  static constexpr int kSize = 4096;
  std::uint8_t table_[kSize];
};

// Room light: the bin's lamps (bin frame, mm, z up) in the camera's frame, soft shadows.
ShadingOptions room_lighting(const BinVariation& look, const StereoRig& rig, bool right,
                             std::uint32_t seed, int threads) {
  const Eigen::Vector3d shift = right ? Eigen::Vector3d(rig.baseline_mm, 0, 0) : Eigen::Vector3d::Zero();
  ShadingOptions options;
  options.lights.clear();
  for (const RoomLamp& lamp : look.lamps) {
    Light light;
    light.position = (rig.left_point(lamp.position) - shift).cast<float>();
    light.intensity = lamp.intensity;
    light.radius = lamp.radius_mm;
    options.lights.push_back(light);
  }
  options.ambient = float(look.ambient);
  options.shadow_samples = 8;
  options.seed = seed;
  options.threads = threads;
  return options;
}

struct View {
  RaycastImages cast;
  cv::Mat passive, active;  // linear radiance
};

View render_view(RenderScene& scene, const std::vector<Pose>& world_poses, const StereoRig& rig,
                 bool right, const BinSimSettings& settings, const BinVariation& look,
                 const DotPattern& pattern, std::uint32_t seed) {
  for (int i = 0; i < int(world_poses.size()); ++i) {
    scene.set_pose(i, right ? rig.to_right(world_poses[i]) : rig.to_left(world_poses[i]));
  }
  scene.commit();
  const PinholeCamera& camera = right ? rig.right : rig.left;
  View view;
  RaycastOptions cast;
  cast.threads = settings.threads;
  view.cast = raycast(scene, camera, cast);
  view.passive = shade_linear(scene, view.cast, room_lighting(look, rig, right, seed, settings.threads));
  Eigen::Vector3d projector = rig.projector_in_left();
  if (right) projector.x() -= rig.baseline_mm;
  view.active = view.passive +
                projector_radiance(scene, view.cast, camera, projector, pattern, settings.threads);
  return view;
}

// The camera: a varied bin's optics and sensor (sensor_model.h), else the fixed Gaussian
// noise after the encoding.
cv::Mat to_8bit(const cv::Mat& radiance, const BinVariation& look, int camera, double noise_sigma,
                std::uint64_t key) {
  static const Srgb8 encode;
  if ((look.aspects & (kVaryCamera | kVaryOptics)) == 0) {
    cv::Mat rgb = encode(radiance);
    apply_camera_effects(rgb, 0.0, noise_sigma, key);
    return rgb;
  }
  cv::Mat rgb = encode(apply_camera_look(radiance, look.cameras[camera], key));
  if ((look.aspects & kVaryCamera) == 0) apply_camera_effects(rgb, 0.0, noise_sigma, key);
  return rgb;
}

// The scene of a bin: the resting parts first (instance ids 0..n-1, the BOP gt ids), each
// a grey drawn from `look` or the varied bin's material, then bin and table. `parts` gets
// the parts, `world_poses` the world pose of every instance.
void compose_bin_scene(const PhysicsResult& physics, const PartLibrary& library,
                       const std::shared_ptr<const Mesh>& bin_mesh,
                       const std::shared_ptr<const Mesh>& table_mesh, SynthRandom& look,
                       const BinVariation& variation, RenderScene& scene, std::vector<BinPart>& parts,
                       std::vector<Pose>& world_poses) {
  std::vector<int> mesh_of_part(library.size(), -1);
  for (const RestingPart& resting : physics.parts) {
    if (mesh_of_part[resting.part] < 0) mesh_of_part[resting.part] = scene.add_mesh(library.part(resting.part).mesh);
    BinPart part;
    part.part = resting.part;
    part.obj_id = library.part(resting.part).obj_id;
    part.world = resting.world;
    // Dark to light grey plastic, or the varied bin's material.
    Material material;
    if (variation.aspects & kVaryMaterial) {
      material = variation.part_materials[parts.size()];
    } else {
      material.albedo = Eigen::Vector3f::Constant(float(look.uniform(0.12, 0.75)));
    }
    part.albedo = material.albedo;
    scene.add_instance(mesh_of_part[resting.part], Pose{}, material);
    world_poses.push_back(part.world);
    parts.push_back(part);
  }
  Material bin_material;
  bin_material.albedo = Eigen::Vector3f::Constant(0.45f);
  bin_material.specular = 0.1f;
  if (variation.aspects & kVaryMaterial) bin_material = variation.bin_material;
  scene.add_instance(scene.add_mesh(bin_mesh), Pose{}, bin_material);
  world_poses.push_back(Pose{});
  Material table_material;
  table_material.albedo = Eigen::Vector3f(0.30f, 0.29f, 0.27f);
  table_material.specular = 0.05f;
  scene.add_instance(scene.add_mesh(table_mesh), Pose{}, table_material);
  world_poses.push_back(Pose{});
}

}  // namespace

cv::Mat disparity_from_depth(const StereoRig& rig, const cv::Mat& depth) {
  cv::Mat disparity(depth.size(), CV_32FC1);
  for (int y = 0; y < depth.rows; ++y) {
    for (int x = 0; x < depth.cols; ++x) {
      const float z = depth.at<float>(y, x);
      disparity.at<float>(y, x) =
          z > 0.0f ? float(rig.disparity(z)) : std::numeric_limits<float>::infinity();
    }
  }
  return disparity;
}

cv::Mat nonoccluded_left(const StereoRig& rig, const cv::Mat& depth0, const cv::Mat& instance0,
                         const cv::Mat& depth1, const cv::Mat& instance1) {
  cv::Mat mask = cv::Mat::zeros(depth0.size(), CV_8UC1);
  for (int y = 0; y < depth0.rows; ++y) {
    for (int x = 0; x < depth0.cols; ++x) {
      const float z = depth0.at<float>(y, x);
      if (z <= 0.0f) continue;
      const double u = x - rig.disparity(z);
      if (u < 0.0 || u > depth0.cols - 1.0) continue;
      const double tolerance = std::max(2.0, 0.005 * z);
      const int id = instance0.at<int>(y, x);
      for (int v : {int(std::floor(u)), int(std::ceil(u))}) {
        if (instance1.at<int>(y, v) == id && std::abs(depth1.at<float>(y, v) - z) <= tolerance) {
          mask.at<std::uint8_t>(y, x) = 255;
          break;
        }
      }
    }
  }
  return mask;
}

BinSimulator::BinSimulator(const BinSimSettings& settings, const PartLibrary& parts)
    : settings_(settings), parts_(parts) {
  settings_.check();
  rig_ = make_stereo_rig(settings_.rig);
  for (int i = 0; i < parts_.size(); ++i) hulls_.push_back(make_part_hull(*parts_.part(i).mesh));
  pattern_ = std::make_unique<DotPattern>(settings_.projector);
  bin_mesh_ = std::make_shared<const Mesh>(make_bin_mesh(settings_.bin));
  table_mesh_ = std::make_shared<const Mesh>(make_table_mesh(settings_.bin));
}

BinSimulator::~BinSimulator() = default;

BinViews BinSimulator::simulate(std::uint32_t seed, std::int64_t index) const {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  BinViews views;

  // Which parts, in which order they fall.
  SynthRandom count_random(seed, index, kStreamCount);
  const int count = count_random.integer(settings_.min_parts, settings_.max_parts);
  std::vector<int> order;
  for (int i = 0; i < count; ++i) order.push_back(count_random.integer(0, parts_.size() - 1));
  views.physics = drop_parts(hulls_, order, settings_.bin, settings_.physics,
                             SynthRandom(seed, index, kStreamDrop));
  const Clock::time_point physics_done = Clock::now();
  views.physics_ms = std::chrono::duration<double, std::milli>(physics_done - start).count();

  // How this bin looks: the settings', or drawn per bin (bin_variation.h).
  views.variation = draw_bin_variation(settings_, rig_.t_cw.z() + 800.0, seed, index,
                                       int(views.physics.parts.size()));
  const BinVariation& variation = views.variation;
  std::unique_ptr<DotPattern> varied_pattern;
  if (variation.aspects & kVaryProjector) {
    ProjectorSettings projector = settings_.projector;
    projector.power = float(variation.projector_power);
    projector.dot_sigma_degrees = variation.dot_sigma_degrees;
    projector.blur_sigma_degrees = variation.dot_blur_degrees;
    varied_pattern = std::make_unique<DotPattern>(projector);
  }
  const DotPattern& pattern = varied_pattern ? *varied_pattern : *pattern_;
  views.projector = projector_calib(rig_, pattern.settings());
  views.pattern = render_pattern_image(pattern, views.projector);

  // The scene: parts first (instance ids 0..n-1, the BOP gt ids), then bin and table.
  SynthRandom look(seed, index, kStreamLook);
  RenderScene scene;
  std::vector<Pose> world_poses;
  compose_bin_scene(views.physics, parts_, bin_mesh_, table_mesh_, look, variation, scene, views.parts,
                    world_poses);

  const std::uint32_t shading_seed = static_cast<std::uint32_t>(SynthRandom(seed, index, kStreamLook + 0x10).next_u64());
  const View right = render_view(scene, world_poses, rig_, true, settings_, variation, pattern, shading_seed);
  const View left = render_view(scene, world_poses, rig_, false, settings_, variation, pattern,
                                shading_seed);  // scene left at the left poses

  const auto noise_key = [&](int image) { return SynthRandom(seed, index, kStreamNoise + 0x100 * image).next_u64(); };
  const double sigma = settings_.noise_sigma;
  views.im0 = to_8bit(left.active, variation, 0, sigma, noise_key(0));
  views.im1 = to_8bit(right.active, variation, 1, sigma, noise_key(1));
  views.im0_passive = to_8bit(left.passive, variation, 0, sigma, noise_key(2));
  views.im1_passive = to_8bit(right.passive, variation, 1, sigma, noise_key(3));
  views.disp0 = disparity_from_depth(rig_, left.cast.depth);
  views.disp1 = disparity_from_depth(rig_, right.cast.depth);
  views.nocc0 = nonoccluded_left(rig_, left.cast.depth, left.cast.instance, right.cast.depth,
                                 right.cast.instance);

  // The left view as a BOP image.
  AnnotatedImage& image = views.left;
  image.scene_id = 0;
  image.im_id = static_cast<int>(index);
  image.rgb = views.im0_passive;
  image.depth = left.cast.depth.clone();
  image.camera.K << rig_.left.fx, 0.0, rig_.left.cx, 0.0, rig_.left.fy, rig_.left.cy, 0.0, 0.0, 1.0;
  image.camera.extra = {{"baseline", rig_.baseline_mm}, {"doffs", rig_.doffs}};
  RaycastOptions cast;
  cast.threads = settings_.threads;
  const std::vector<cv::Mat> amodal = amodal_masks(scene, rig_.left, cast);
  for (int i = 0; i < int(views.parts.size()); ++i) {
    PartAnnotation part;
    part.obj_id = views.parts[i].obj_id;
    const Pose pose = rig_.to_left(views.parts[i].world);
    part.cam_R_m2c = pose.R;
    part.cam_t_m2c = pose.t;
    part.mask = amodal[i];
    part.mask_visib = visible_mask(left.cast, i);
    fill_gt_info(part, image.depth);
    image.parts.push_back(std::move(part));
  }
  views.render_ms = std::chrono::duration<double, std::milli>(Clock::now() - physics_done).count();
  return views;
}

}  // namespace flexsight

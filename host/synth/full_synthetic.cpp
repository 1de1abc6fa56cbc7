#include "host/synth/full_synthetic.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <climits>
#include <opencv2/imgproc.hpp>

#include "host/render/raycaster.h"
#include "host/render/shading.h"
#include "host/synth/appearance.h"
#include "host/synth/background.h"
#include "host/synth/camera_effects.h"
#include "host/dataset/gt_info.h"
#include "host/synth/part_placement.h"
#include "host/synth/synth_random.h"

namespace flexsight {
namespace {

using Clock = std::chrono::steady_clock;
using synth_detail::SynthRandom;

// Milliseconds since `since`, which moves on to now.
double lap_ms(Clock::time_point& since) {
  const Clock::time_point now = Clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - since).count();
  since = now;
  return ms;
}

// The post-processing of one image, drawn before anything else: the in-plane rotation
// decides the camera in which the parts are placed.
struct Augmentation {
  double rotation_radians = 0.0;
  bool flip_horizontal = false, flip_vertical = false;
  double blur_sigma = 0.0, noise_sigma = 0.0;
  std::uint64_t noise_key = 0;
};

Augmentation draw_augmentation(const FullSyntheticSettings& settings, std::uint32_t seed,
                               std::int64_t image_index) {
  SynthRandom random(seed, image_index, synth_detail::kStreamAugment);
  Augmentation a;
  const double max = settings.max_rotation_degrees * M_PI / 180.0;
  a.rotation_radians = random.uniform(-max, max);
  a.flip_horizontal = random.chance(settings.horizontal_flip_probability);
  a.flip_vertical = random.chance(settings.vertical_flip_probability);
  const bool blur = random.chance(settings.blur_probability);
  const double blur_sigma = random.uniform(0.0, settings.max_blur_sigma);
  a.blur_sigma = blur ? blur_sigma : 0.0;
  a.noise_sigma = random.uniform(0.0, settings.max_noise_sigma);
  a.noise_key = SynthRandom(seed, image_index, synth_detail::kStreamNoise).next_u64();
  return a;
}

// The mean of the kept parts' centres (camera frame) and the distance from it that no
// part's bounding sphere crosses: where the lights may go.
void parts_extent(const RenderScene& scene, const Placement& placement, Eigen::Vector3d& centre,
                  double& reach) {
  std::vector<Eigen::Vector3d> centres;
  for (const PlacedPart& part : placement.parts) {
    const Instance& instance = scene.instance(part.instance);
    const Mesh& mesh = scene.mesh(instance.mesh);
    centres.push_back(instance.pose.R * mesh.bounds.center().cast<double>() + instance.pose.t);
  }
  centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& c : centres) centre += c / double(centres.size());
  reach = 0.0;
  for (size_t i = 0; i < centres.size(); ++i) {
    const Mesh& mesh = scene.mesh(scene.instance(placement.parts[i].instance).mesh);
    reach = std::max(reach, (centres[i] - centre).norm() + 0.5 * mesh.diameter);
  }
}

int flip_code(const Augmentation& a) {
  return a.flip_horizontal && a.flip_vertical ? -1 : (a.flip_horizontal ? 1 : 0);
}

// An image flipped by the drawn flips (none: unchanged).
void flip_image(cv::Mat& image, const Augmentation& a) {
  if (!a.flip_horizontal && !a.flip_vertical) return;
  cv::Mat flipped;
  cv::flip(image, flipped, flip_code(a));
  image = flipped;
}

// The full-size amodal mask of a part from its patch, flipped as the picture was.
cv::Mat amodal_mask(const AmodalPatch& patch, const cv::Size& size, const Augmentation& a) {
  cv::Mat mask = cv::Mat::zeros(size, CV_8UC1);
  if (patch.area.empty()) return mask;
  cv::Mat on;
  cv::compare(patch.depth, 0.0, on, cv::CMP_GT);
  cv::Rect area = patch.area;
  if (a.flip_horizontal) area.x = size.width - area.x - area.width;
  if (a.flip_vertical) area.y = size.height - area.y - area.height;
  flip_image(on, a);
  on.copyTo(mask(area));
  return mask;
}

// The image and its annotations: the flips first (reflections: the poses are stored
// reflected, see annotated_image.h), then every annotation from the final masks. `rgb`
// and `images` are flipped in place.
AnnotatedImage annotated_image(const FullSyntheticSettings& settings, const PartLibrary& parts,
                               const RenderScene& scene, const Placement& placement,
                               const PinholeCamera& camera, const Augmentation& augmentation,
                               std::int64_t image_index, cv::Mat& rgb, RaycastImages& images) {
  flip_image(rgb, augmentation);
  flip_image(images.depth, augmentation);
  flip_image(images.instance, augmentation);
  const Eigen::Matrix3d F = Eigen::Vector3d(augmentation.flip_horizontal ? -1.0 : 1.0,
                                            augmentation.flip_vertical ? -1.0 : 1.0, 1.0)
                                .asDiagonal();
  const cv::Size size(camera.width, camera.height);
  AnnotatedImage image;
  image.im_id = image_index >= 0 && image_index <= INT_MAX ? static_cast<int>(image_index) : 0;
  image.rgb = rgb;
  if (settings.store_depth) {
    image.depth = images.depth.clone();
    apply_stereo_depth_noise(image.depth, camera.fx, settings.depth_noise,
                             augmentation.noise_key ^ 0xD3E7B0A5ULL);
  }
  image.camera.K << camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0;
  image.flipped_horizontally = augmentation.flip_horizontal;
  image.flipped_vertically = augmentation.flip_vertical;
  for (const PlacedPart& placed : placement.parts) {
    const Pose& pose = scene.instance(placed.instance).pose;
    PartAnnotation part;
    part.obj_id = parts.part(placed.part).obj_id;
    part.cam_R_m2c = F * pose.R;
    part.cam_t_m2c = F * pose.t;
    part.mask = amodal_mask(placed.amodal, size, augmentation);
    cv::compare(images.instance, placed.instance, part.mask_visib, cv::CMP_EQ);
    fill_gt_info(part, images.depth);
    if (!settings.store_masks) {
      part.mask.release();
      part.mask_visib.release();
    }
    image.parts.push_back(std::move(part));
  }
  return image;
}

}  // namespace

AnnotatedImage render_full_synthetic(const FullSyntheticSettings& settings,
                                     const PartLibrary& parts, const BackgroundLibrary& backgrounds,
                                     std::uint32_t seed, std::int64_t image_index,
                                     FullSyntheticStats* stats) {
  settings.check();
  FullSyntheticStats local;
  FullSyntheticStats& timing = stats != nullptr ? *stats : local;
  timing = {};
  Clock::time_point clock = Clock::now();
  const PinholeCamera camera = settings.camera();
  const Augmentation augmentation = draw_augmentation(settings, seed, image_index);
  // Turning the picture by a about the principal point is turning the camera about its
  // optical axis (fx == fy): the parts are rendered in the turned camera, so masks,
  // depth and poses need no resampling.
  const Eigen::Matrix3d camera_rotation =
      Eigen::AngleAxisd(augmentation.rotation_radians, Eigen::Vector3d::UnitZ()).toRotationMatrix();

  // The parts, under the occlusion cap.
  const ScenePool::Lease scene = parts.scenes().acquire();
  const Placement placement =
      place_parts(settings, parts, *scene, camera, camera_rotation, seed, image_index);
  timing.pose_attempts = placement.attempts;
  timing.parts_dropped = placement.dropped;
  timing.scene_setup_ms = scene->take_setup_ms();
  timing.sampling_ms = lap_ms(clock) - timing.scene_setup_ms;

  // The final cast, within the kept parts' projected boxes only: the other instances
  // are parked behind the camera, so no ray outside those boxes meets anything.
  RaycastOptions raycast_options;
  raycast_options.threads = 1;
  for (const PlacedPart& placed : placement.parts) {
    if (!placed.amodal.area.empty()) raycast_options.areas.push_back(placed.amodal.area);
  }
  RaycastImages images = raycast(scene->scene(), camera, raycast_options);
  timing.raycast_ms = lap_ms(clock);

  Eigen::Vector3d centre;
  double reach = 0.0;
  parts_extent(scene->scene(), placement, centre, reach);
  const ShadingOptions lighting =
      draw_lighting(settings, centre, reach, camera_rotation, seed, image_index);
  const cv::Mat shaded = shade(scene->scene(), images, lighting);
  timing.shading_ms = lap_ms(clock);

  // The parts over the background, where a ray met one (no anti-aliasing), then the
  // camera's blur and noise over both.
  cv::Mat rgb = draw_background(
      {settings.min_crop_scale, settings.max_crop_aspect_change,
       settings.background_flip_probability},
      backgrounds, camera, camera_rotation, seed, image_index);
  cv::Mat covered;
  cv::compare(images.instance, 0, covered, cv::CMP_GE);
  shaded.copyTo(rgb, covered);
  apply_camera_effects(rgb, augmentation.blur_sigma, augmentation.noise_sigma,
                       augmentation.noise_key);
  timing.compositing_ms = lap_ms(clock);

  // Flips, then every annotation from the final masks.
  AnnotatedImage image = annotated_image(settings, parts, scene->scene(), placement, camera, augmentation,
                                         image_index, rgb, images);
  timing.augmentation_ms = lap_ms(clock);
  return image;
}

}  // namespace flexsight

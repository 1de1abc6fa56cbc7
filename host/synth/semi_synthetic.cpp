#include "host/synth/semi_synthetic.h"

#include <Eigen/Core>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "host/dataset/gt_info.h"
#include "host/synth/background.h"
#include "host/synth/camera_effects.h"
#include "host/synth/patch_paste.h"
#include "host/synth/synth_random.h"

namespace flexsight {
namespace {

using synth_detail::SynthRandom;

PatchPlacement draw_placement(const SemiSyntheticSettings& settings, const Patch& patch,
                              SynthRandom& random) {
  PatchPlacement placement;
  const double diagonal = std::hypot(patch.rgb.cols, patch.rgb.rows);
  const double size =
      settings.width * random.log_uniform(settings.min_part_size, settings.max_part_size);
  placement.scale = size / diagonal;
  placement.angle_degrees =
      random.uniform(-settings.max_rotation_degrees, settings.max_rotation_degrees);
  placement.mirror = random.chance(settings.mirror_probability);
  placement.gain = random.uniform(settings.min_contrast, settings.max_contrast);
  placement.offset = random.uniform(-settings.max_brightness, settings.max_brightness);
  // The patch's centre anywhere in the image: a part may be cut by the border, as in
  // the full-synthetic images.
  placement.centre = {random.uniform(0.0, settings.width - 1.0),
                      random.uniform(0.0, settings.height - 1.0)};
  return placement;
}

struct Pasted {
  int patch = 0;
  PlacedPatch placed;
  cv::Mat visible;  // the part's mask minus what later pastes cover
  int pixels = 0;   // of the whole mask within the image
};

// Whether `candidate`, pasted over `kept`, leaves every part (itself included) at
// least min_visible_fraction visible.
bool keeps_everyone_visible(const std::vector<Pasted>& kept, const PlacedPatch& candidate,
                            double min_visible_fraction) {
  if (cv::countNonZero(candidate.mask) == 0) return false;
  for (const Pasted& part : kept) {
    const int still = cv::countNonZero(part.visible & ~candidate.mask);
    if (still < min_visible_fraction * part.pixels) return false;
  }
  return true;
}

}  // namespace

AnnotatedImage render_semi_synthetic(const SemiSyntheticSettings& settings,
                                     const std::vector<Patch>& patches,
                                     const BackgroundLibrary& backgrounds, std::uint32_t seed,
                                     std::int64_t image_index) {
  if (patches.empty()) throw std::invalid_argument("render_semi_synthetic: no patch");
  settings.check();
  const PinholeCamera camera = settings.camera();
  const cv::Size size(settings.width, settings.height);
  cv::Mat rgb = draw_background({settings.min_crop_scale, settings.max_crop_aspect_change,
                                 settings.background_flip_probability},
                                backgrounds, camera, Eigen::Matrix3d::Identity(), seed,
                                image_index);

  SynthRandom scene_random(seed, image_index, synth_detail::kStreamScene);
  const int count = scene_random.integer(settings.min_parts, settings.max_parts);
  std::vector<Pasted> kept;
  for (int slot = 0; slot < count; ++slot) {
    // Each slot draws from its own stream, so a rejected placement of one part does
    // not change what the next part draws.
    SynthRandom random(seed, image_index, synth_detail::kStreamPart + slot);
    const int patch_index = random.integer(0, static_cast<int>(patches.size()) - 1);
    for (int attempt = 0; attempt < settings.pose_attempts; ++attempt) {
      PlacedPatch placed =
          place_patch(patches[patch_index], draw_placement(settings, patches[patch_index], random),
                      size);
      if (!keeps_everyone_visible(kept, placed, settings.min_visible_fraction)) continue;
      for (Pasted& part : kept) part.visible &= ~placed.mask;
      Pasted pasted;
      pasted.patch = patch_index;
      pasted.visible = placed.mask.clone();
      pasted.pixels = cv::countNonZero(placed.mask);
      pasted.placed = std::move(placed);
      kept.push_back(std::move(pasted));
      break;
    }
  }

  for (const Pasted& part : kept) paste_patch(rgb, part.placed);
  SynthRandom effects(seed, image_index, synth_detail::kStreamAugment);
  const bool blur = effects.chance(settings.blur_probability);
  const double blur_sigma = effects.uniform(0.0, settings.max_blur_sigma);
  const double noise_sigma = effects.uniform(0.0, settings.max_noise_sigma);
  apply_camera_effects(rgb, blur ? blur_sigma : 0.0, noise_sigma,
                       SynthRandom(seed, image_index, synth_detail::kStreamNoise).next_u64());

  AnnotatedImage image;
  image.rgb = rgb;
  image.camera.K << camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0;
  image.camera.extra["pose_unknown"] = true;
  for (const Pasted& pasted : kept) {
    PartAnnotation part;
    part.obj_id = patches[pasted.patch].obj_id;
    part.mask = pasted.placed.mask;
    part.mask_visib = pasted.visible;
    fill_gt_info(part, cv::Mat());
    if (!settings.store_masks) {
      part.mask.release();
      part.mask_visib.release();
    }
    image.parts.push_back(std::move(part));
  }
  return image;
}

}  // namespace flexsight

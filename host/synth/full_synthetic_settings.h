#pragma once
// What the full-synthetic generator draws from: every distribution's range with its
// default and the reason for it (docs/synth.md has the longer story). The paper names
// the parameters it randomised (number and type of parts, pose, occlusion, colour,
// light type and position, Gaussian noise, flips and a slight in-plane rotation) but
// not their ranges; where a default is ours, the comment says why.
#include "host/render/raycaster.h"
#include "host/synth/background_effects.h"
#include "host/synth/depth_noise.h"

namespace flexsight {

struct FullSyntheticSettings : BackgroundEffects {
  // Image size in pixels (--width, --height): the SSD-MobileNet detector's 300x300 input.
  int width = 300;
  int height = 300;
  // Horizontal field of view in degrees (--fov); fx = fy = (width / 2) / tan(fov / 2),
  // principal point at the image centre ((width - 1) / 2, (height - 1) / 2), so that
  // flips and the in-plane rotation map the camera onto itself. The paper gives no
  // camera for its synthetic images; 50 lies between the T-LESS Primesense images (37)
  // and common RGB-D sensors (58-70). Part sizes are drawn in pixels, so the field of
  // view only sets how strong the perspective is.
  double horizontal_fov_degrees = 50.0;

  // Parts per image, uniform in [min_parts, max_parts] (--min-parts, --max-parts); each
  // part's model uniform over the library, repeats allowed.
  int min_parts = 1;
  int max_parts = 6;
  // Projected diameter of a part (the model's diameter over its distance, times the
  // focal length) as a fraction of the image width (--min-size, --max-size): 30 to 250
  // pixels at 300 wide, from parts the detector's finest feature map can still resolve
  // to parts that nearly fill the picture. Drawn log-uniform, so every doubling of size
  // is equally likely, as the detector's feature maps halve from layer to layer.
  double min_part_size = 0.1;
  double max_part_size = 0.83;
  // Least visible fraction of every kept part (--min-visible): visible pixels over the
  // pixels of its whole silhouette within the image. Half: a part less than half seen
  // is often not recognisable as its model, and teaching the detector to fire on such
  // fragments would teach it false positives on texture-less clutter.
  double min_visible_fraction = 0.5;
  // Poses tried for a part whose placement breaks the cap (its own or an earlier
  // part's visibility) before it is dropped (--pose-attempts). The first part is never
  // dropped for occlusion: nothing hides it.
  int pose_attempts = 5;

  // Albedo: a grey level in linear reflectance, uniform in [min_grey, max_grey]
  // (--min-grey, --max-grey), each channel within +-max_tint of it (--max-tint): the
  // T-LESS parts are dark to mid grey plastic, "color of the render" is randomised.
  double min_grey = 0.08;
  double max_grey = 0.6;
  double max_tint = 0.04;
  // Blinn-Phong highlight: weight uniform in [min_specular, max_specular], exponent
  // log-uniform in [min_shininess, max_shininess] (--min-specular, ...): from matte
  // plastic with a broad weak highlight to metal-ish parts with a tight bright one.
  double min_specular = 0.05;
  double max_specular = 0.6;
  double min_shininess = 8.0;
  double max_shininess = 256.0;

  // Lights: a count uniform in [min_lights, max_lights] (--min-lights, --max-lights;
  // the renderer takes up to three), each a spot with probability spot_probability
  // (--spot-probability, the paper's "diffuse or spotlight"), otherwise a point light,
  // somewhere in front of the parts (docs/synth.md). A light is a disc of some radius,
  // hence casts soft shadows, with probability soft_shadow_probability
  // (--soft-shadows), with shadow_samples rays per lit pixel (--shadow-samples; 4 keeps
  // the image fast, the penumbra is then a little grainy, which the noise hides). Soft
  // shadows are the costly part of an image (four shadow rays per lit pixel instead of
  // one): at 0.3 rather than 0.5 a 1280x960 image takes about 15 % less time.
  int min_lights = 1;
  int max_lights = 3;
  double spot_probability = 0.5;
  double soft_shadow_probability = 0.3;
  int shadow_samples = 4;
  // A light at the camera (no shadow) with probability camera_light_probability
  // (--camera-light), and an ambient term uniform in [min_ambient, max_ambient]
  // (--min-ambient, --max-ambient) for what inter-reflections would bring.
  double camera_light_probability = 0.25;
  double min_ambient = 0.05;
  double max_ambient = 0.3;

  // Background crop and camera effects: BackgroundEffects (background_effects.h).

  // Post-processing of the whole image (the paper's flips and slight rotation about the
  // optical axis): flips with these probabilities (--hflip, --vflip; 0.5 each, as the
  // random flips of the TensorFlow Object Detection API the paper trained with), and a
  // rotation uniform in +-max_rotation_degrees about the principal point (--max-rotation).
  double horizontal_flip_probability = 0.5;
  double vertical_flip_probability = 0.5;
  double max_rotation_degrees = 10.0;

  // What to produce besides the picture and the annotations (--no-masks, --no-depth):
  // masks take two full-size images per part, depth one float image.
  bool store_masks = true;
  bool store_depth = true;
  // The stored depth as a stereo camera would measure it (host/synth/depth_noise.h:
  // --depth-noise disparity sigma in pixels, --depth-baseline mm, --depth-dropout pixels
  // at discontinuities); exact depth by default. Annotations use the exact depth.
  StereoDepthNoise depth_noise;

  // The camera of every image of these settings (after check()).
  PinholeCamera camera() const;
  // Throws InputError("option --<name>", problem) for the first value out of range.
  void check() const;
};

}  // namespace flexsight

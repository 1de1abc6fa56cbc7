#pragma once
// The background crop and the camera effects that both synthetic generators (full and semi)
// apply to a whole composite, with one set of defaults and reasons.

namespace flexsight {

struct BackgroundEffects {
  // Background: a random image of the library, a crop of it whose shorter side is a
  // fraction uniform in [min_crop_scale, 1] of the largest crop that fits
  // (--min-crop-scale), of aspect within a factor exp(+-max_crop_aspect_change) of the
  // output's (--crop-aspect-change), resized to width x height, mirrored left-right with
  // probability background_flip_probability (--background-flip).
  double min_crop_scale = 0.5;
  double max_crop_aspect_change = 0.1;
  double background_flip_probability = 0.5;

  // Camera effects on the whole composite, so that part and background share them (a
  // part with its own grain or sharpness would be a cue real images lack): a Gaussian
  // blur of sigma uniform in [0, max_blur_sigma] pixels with probability
  // blur_probability (--blur-probability, --max-blur), then Gaussian noise of sigma
  // uniform in [0, max_noise_sigma] grey levels (--max-noise).
  double blur_probability = 0.5;
  double max_blur_sigma = 1.0;
  double max_noise_sigma = 6.0;

  // Throws InputError naming the option of the first value out of range.
  void check_effects() const;
};

}  // namespace flexsight

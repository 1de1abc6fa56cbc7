#include "host/synth/background_effects.h"

#include <cmath>

#include "host/synth/settings_checks.h"

namespace flexsight {

using namespace synth_detail;

void BackgroundEffects::check_effects() const {
  if (!(std::isfinite(min_crop_scale) && min_crop_scale > 0.0 && min_crop_scale <= 1.0)) {
    fail_option("min-crop-scale", "must be in (0, 1] (got " + number_text(min_crop_scale) + ")");
  }
  in_range("crop-aspect-change", max_crop_aspect_change, 0.0, 1.0);
  probability("background-flip", background_flip_probability);
  probability("blur-probability", blur_probability);
  in_range("max-blur", max_blur_sigma, 0.0, 10.0);
  in_range("max-noise", max_noise_sigma, 0.0, 100.0);
}

}  // namespace flexsight

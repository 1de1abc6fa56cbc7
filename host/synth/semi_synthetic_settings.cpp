#include "host/synth/semi_synthetic_settings.h"

#include <cmath>

#include "host/synth/settings_checks.h"

namespace flexsight {

using namespace synth_detail;

PinholeCamera SemiSyntheticSettings::camera() const { return centred_camera(width, height, width); }

void SemiSyntheticSettings::check() const {
  image_size(width, height);
  part_count(min_parts, max_parts);
  in_range("min-size", min_part_size, 1e-3, 4.0);
  in_range("max-size", max_part_size, 1e-3, 4.0);
  ordered("min-size", min_part_size, "max-size", max_part_size);
  in_range("max-rotation", max_rotation_degrees, 0.0, 180.0);
  probability("mirror", mirror_probability);
  in_range("max-brightness", max_brightness, 0.0, 255.0);
  in_range("min-contrast", min_contrast, 0.0, 10.0);
  in_range("max-contrast", max_contrast, 0.0, 10.0);
  ordered("min-contrast", min_contrast, "max-contrast", max_contrast);
  probability("min-visible", min_visible_fraction);
  int_in_range("pose-attempts", pose_attempts, 1, 1000);
  check_effects();
}

}  // namespace flexsight

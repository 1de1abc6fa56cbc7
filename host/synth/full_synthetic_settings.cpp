#include "host/synth/full_synthetic_settings.h"

#include <cmath>
#include <sstream>
#include <string>

#include "host/io/input_error.h"
#include "host/synth/settings_checks.h"

namespace flexsight {
using namespace synth_detail;

PinholeCamera FullSyntheticSettings::camera() const {
  return centred_camera(width, height,
                        0.5 * width / std::tan(0.5 * horizontal_fov_degrees * M_PI / 180.0));
}

void FullSyntheticSettings::check() const {
  image_size(width, height);
  in_range("fov", horizontal_fov_degrees, 1.0, 170.0);

  part_count(min_parts, max_parts);
  if (!(std::isfinite(min_part_size) && min_part_size > 0.0)) {
    fail_option("min-size", "must be positive (got " + number_text(min_part_size) + ")");
  }
  in_range("max-size", max_part_size, 1e-3, 4.0);
  ordered("min-size", min_part_size, "max-size", max_part_size);
  probability("min-visible", min_visible_fraction);
  int_in_range("pose-attempts", pose_attempts, 1, 1000);

  in_range("min-grey", min_grey, 0.0, 1.0);
  in_range("max-grey", max_grey, 0.0, 1.0);
  ordered("min-grey", min_grey, "max-grey", max_grey);
  in_range("max-tint", max_tint, 0.0, 0.5);
  in_range("min-specular", min_specular, 0.0, 10.0);
  in_range("max-specular", max_specular, 0.0, 10.0);
  ordered("min-specular", min_specular, "max-specular", max_specular);
  in_range("min-shininess", min_shininess, 1.0, 1e4);
  in_range("max-shininess", max_shininess, 1.0, 1e4);
  ordered("min-shininess", min_shininess, "max-shininess", max_shininess);

  int_in_range("min-lights", min_lights, 1, 3);
  int_in_range("max-lights", max_lights, 1, 3);
  ordered("min-lights", min_lights, "max-lights", max_lights);
  probability("spot-probability", spot_probability);
  probability("soft-shadows", soft_shadow_probability);
  int_in_range("shadow-samples", shadow_samples, 1, 256);
  probability("camera-light", camera_light_probability);
  in_range("min-ambient", min_ambient, 0.0, 10.0);
  in_range("max-ambient", max_ambient, 0.0, 10.0);
  ordered("min-ambient", min_ambient, "max-ambient", max_ambient);

  check_effects();

  probability("hflip", horizontal_flip_probability);
  probability("vflip", vertical_flip_probability);
  in_range("max-rotation", max_rotation_degrees, 0.0, 180.0);
  depth_noise.check();
}

}  // namespace flexsight

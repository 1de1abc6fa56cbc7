#include "host/sim/bin_settings.h"

#include <cmath>
#include <cstdio>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

void require_positive(double value, const std::string& option) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InputError("option " + option, "must be a positive number, got " + std::to_string(value));
  }
}

void require_nonnegative(double value, const std::string& option) {
  if (!std::isfinite(value) || value < 0.0) {
    throw InputError("option " + option, "must be a number >= 0, got " + std::to_string(value));
  }
}

}  // namespace

void BinSimSettings::check() const {
  make_stereo_rig(rig);
  require_positive(bin.length_mm, "--bin");
  require_positive(bin.width_mm, "--bin");
  require_positive(bin.wall_height_mm, "--bin");
  require_positive(bin.wall_thickness_mm, "--wall-thickness");
  require_positive(bin.floor_thickness_mm, "--floor-thickness");
  const double outer_x = bin.length_mm + 2.0 * bin.wall_thickness_mm;
  const double outer_y = bin.width_mm + 2.0 * bin.wall_thickness_mm;
  const double outer_z = bin.wall_height_mm;
  if (outer_x > rig.volume.width || outer_y > rig.volume.height || outer_z > rig.volume.depth) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "the bin (%gx%g mm outside its walls, %g mm high) does not fit in the %gx%gx%g mm "
                  "working volume",
                  outer_x, outer_y, outer_z, rig.volume.width, rig.volume.height, rig.volume.depth);
    throw InputError("option --bin", text);
  }
  if (min_parts < 1 || max_parts > 200 || min_parts > max_parts) {
    throw InputError("option --parts", "expected MIN..MAX with 1 <= MIN <= MAX <= 200, got " +
                                           std::to_string(min_parts) + ".." +
                                           std::to_string(max_parts));
  }
  projector.check();
  require_nonnegative(noise_sigma, "--noise");
  require_nonnegative(room_light, "--room-light");
  require_nonnegative(ambient, "--ambient");
  if (threads < 0) throw InputError("option --threads", "must be >= 0");
}

}  // namespace flexsight

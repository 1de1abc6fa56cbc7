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
  if ((vary & ~unsigned(kVaryAll)) != 0) throw InputError("option --vary", "unknown aspect bits");
  if (!(noise_level_min >= 0.0 && noise_level_min <= noise_level_max && noise_level_max <= 1.0)) {
    throw InputError("option --noise-level", "expected LO..HI with 0 <= LO <= HI <= 1, got " +
                                                 std::to_string(noise_level_min) + ".." +
                                                 std::to_string(noise_level_max));
  }
}

void use_dense_pile(BinSimSettings& settings) {
  settings.pile = BinPile::dense;
  settings.min_parts = 30;
  settings.max_parts = 80;
  settings.physics.wave_size = 10;
  // Within a wave the parts fall 0.1 s apart (each starts above everything, falling
  // parts included); the wave's settling replaces the sparse pile's 0.3 s per part.
  settings.physics.drop_interval_s = 0.1;
  // Each wave heaps up around its own point (a box of parts tipped in): 60 mm, a couple
  // of part sizes.
  settings.physics.heap_sigma_mm = 60.0;
  // A pile several layers deep keeps shivering by a few hundredths of a radian per second
  // (the contacts of one island trade tiny impulses); the tip of a 60 mm part turning at
  // 0.15 rad/s moves 4.5 mm/s, the same as the linear threshold.
  settings.physics.rest_angular_rad_s = 0.15;
}

}  // namespace flexsight

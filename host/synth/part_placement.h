#pragma once
// The parts of one image: which models, at which poses, in which materials, under the
// occlusion cap. Each part's pose is drawn (size, position, rotation), cast alone, and
// kept only if the part and every part kept before it stay at least
// min_visible_fraction visible; otherwise another pose is drawn, up to pose_attempts
// times, and then the part is dropped. Visibility comes from z-compositing the parts'
// amodal depths (solo_cast.h), which agree to the bit with the final ray cast.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "host/synth/full_synthetic_settings.h"
#include "host/synth/part_library.h"
#include "host/synth/solo_cast.h"

namespace flexsight {

struct PlacedPart {
  int part = 0;      // index into the library
  int instance = 0;  // in the pooled scene
  AmodalPatch amodal;
};

struct Placement {
  std::vector<PlacedPart> parts;  // at least one
  int attempts = 0;               // poses cast
  int dropped = 0;                // parts given up for the cap
};

// Places the parts of image (seed, image_index) in `scene` (committed on return). The
// poses are drawn in the camera before its in-plane rotation `camera_rotation` (the
// part's centre uniform over that camera's image) and then turned with the camera:
// R = Q R0, t = Q t0, exactly the picture rotated about the principal point (fx == fy).
Placement place_parts(const FullSyntheticSettings& settings, const PartLibrary& library,
                      PooledScene& scene, const PinholeCamera& camera,
                      const Eigen::Matrix3d& camera_rotation, std::uint32_t seed,
                      std::int64_t image_index);

// A rotation uniform on SO(3) from three uniforms in [0, 1) (Shoemake's quaternion).
Eigen::Matrix3d uniform_rotation(double u1, double u2, double u3);

}  // namespace flexsight

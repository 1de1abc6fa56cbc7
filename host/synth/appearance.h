#pragma once
// How the parts look: a random material per part and random lights per image, drawn
// within the ranges of FullSyntheticSettings (docs/synth.md).
#include <Eigen/Core>
#include <cstdint>

#include "host/render/raycaster.h"
#include "host/render/shading.h"
#include "host/synth/full_synthetic_settings.h"
#include "host/synth/synth_random.h"

namespace flexsight {

// Near-grey albedo, highlight weight and exponent.
Material draw_material(const FullSyntheticSettings& settings, synth_detail::SynthRandom& random);

// One to three point or spot lights, the camera light, the ambient term and the shadow
// jitter's seed for image (seed, image_index). The lights are drawn around `centre`
// (the mean of the parts' centres, camera frame, mm), farther from it than `reach`
// (the farthest point of a part's bounding sphere), in the frame of the camera before
// its in-plane rotation `camera_rotation`, then turned with it, so that a rotated image
// shows the same light as the unrotated one turned. One thread (the caller parallelises
// over images).
ShadingOptions draw_lighting(const FullSyntheticSettings& settings, const Eigen::Vector3d& centre,
                             double reach, const Eigen::Matrix3d& camera_rotation,
                             std::uint32_t seed, std::int64_t image_index);

}  // namespace flexsight

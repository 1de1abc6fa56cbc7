#pragma once
// The paper's "semi-synthetic" training images: segmented patches of the parts (real
// photographs in the paper; patch_library.h) pasted on background photographs at
// random places, sizes, turns, brightness and contrast, hiding each other, under the
// same camera blur and noise as the full-synthetic images. Boxes and masks follow the
// pasted pixels. A patch has no 3D pose: the BOP files get an identity pose and the
// camera entry says "pose_unknown" (docs/synth.md).
#include <cstdint>
#include <vector>

#include "host/dataset/annotated_image.h"
#include "host/synth/background_library.h"
#include "host/synth/patch_library.h"
#include "host/synth/semi_synthetic_settings.h"

namespace flexsight {

// Image `image_index` of the data set with this seed: a pure function of its arguments
// (random numbers keyed by (seed, image_index)), made on the calling thread. Parts in
// pasting order (a later one hides an earlier one); each has visib_fract >= the
// settings' min_visible_fraction. Throws std::invalid_argument for no patch.
AnnotatedImage render_semi_synthetic(const SemiSyntheticSettings& settings,
                                     const std::vector<Patch>& patches,
                                     const BackgroundLibrary& backgrounds, std::uint32_t seed,
                                     std::int64_t image_index);

}  // namespace flexsight

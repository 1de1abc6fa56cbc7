#pragma once
// The paper's "full-synthetic" training images: T-LESS CAD parts rendered at random
// poses, in random materials, under random lights, over random natural photographs,
// with noise, blur, flips and a slight in-plane rotation, and the annotations that come
// with them (BOP fields: poses, boxes, pixel counts, visible fractions, masks, depth).
// docs/synth.md describes the distributions and the conventions.
#include <cstdint>

#include "host/dataset/annotated_image.h"
#include "host/synth/background_library.h"
#include "host/synth/full_synthetic_settings.h"
#include "host/synth/part_library.h"

namespace flexsight {

// Where one image's time went (wall-clock milliseconds, one thread) and what the
// occlusion cap cost.
struct FullSyntheticStats {
  // Building the Embree hierarchies of parts that the pooled render scene had not met
  // yet: the first images only.
  double scene_setup_ms = 0.0;
  // Drawing the parts and their poses, casting each alone, the occlusion cap.
  double sampling_ms = 0.0;
  // The final ray cast of the kept parts (depth, ids, normals, points).
  double raycast_ms = 0.0;
  // Lights and shading, shadow rays included.
  double shading_ms = 0.0;
  // Background (decoding, crop, rotation), composite, blur and noise.
  double compositing_ms = 0.0;
  // Flips, masks, boxes, pixel counts and visible fractions.
  double augmentation_ms = 0.0;
  int pose_attempts = 0;  // poses cast for the occlusion cap
  int parts_dropped = 0;  // parts given up under it
};

// Image number `image_index` of the data set with this seed: a pure function of its
// arguments (every random number is keyed by (seed, image_index), see synth_random.h),
// the same bytes whichever thread makes it and in whatever order. Ray casting and
// shading run on the calling thread only (the caller parallelises over images); OpenCV's
// warp and blur use OpenCV's pool unless cv::setNumThreads(1), and Embree's builder its
// own the first time a pooled scene meets a part. Safe to call from several threads at
// once with the same libraries. `settings` must pass check() (it is checked
// here too). The parts are in gt_id order; each has visib_fract >= the settings'
// min_visible_fraction. scene_id is 0 and im_id the image index (0 when it does not fit
// an int): the writer numbers them. `stats`, when given, receives the timings.
AnnotatedImage render_full_synthetic(const FullSyntheticSettings& settings,
                                     const PartLibrary& parts, const BackgroundLibrary& backgrounds,
                                     std::uint32_t seed, std::int64_t image_index,
                                     FullSyntheticStats* stats = nullptr);

}  // namespace flexsight

#pragma once
// What the semi-synthetic generator draws from, with defaults and reasons. Where a
// setting means the same as in the full-synthetic generator (parts per image, sizes,
// occlusion cap, background crop, camera effects), so do default and reason: the two
// data sets differ in where the parts' pixels come from, not in layout.
#include "host/render/raycaster.h"
#include "host/synth/background_effects.h"

namespace flexsight {

struct SemiSyntheticSettings : BackgroundEffects {
  int width = 300;  // --size WxH: the detector's input
  int height = 300;

  // Parts per image, uniform (--min-parts, --max-parts); each a patch drawn uniformly
  // from the patch library, so parts with more patches come more often.
  int min_parts = 1;
  int max_parts = 6;
  // A pasted patch's box diagonal as a fraction of the image width, log-uniform
  // (--min-size, --max-size): the box diagonal of a part seen whole is close to its
  // projected diameter, so 30 to 250 px at 300 wide as in the full-synthetic images.
  double min_part_size = 0.1;
  double max_part_size = 0.83;
  // Turn in the image plane, uniform in +-max_rotation_degrees (--max-rotation): a real
  // view of a part turned about the optical axis is another real view of it (the
  // camera rolled), so any turn is fair.
  double max_rotation_degrees = 180.0;
  // Chance a patch is mirrored (--mirror): as the full-synthetic images' flips (0.5,
  // the TensorFlow Object Detection API's default the paper trained with).
  double mirror_probability = 0.5;
  // Brightness offset uniform in +-max_brightness grey levels and contrast gain uniform
  // in [min_contrast, max_contrast] per patch (--max-brightness, --min-contrast,
  // --max-contrast): the patches come from other lights than the backgrounds.
  double max_brightness = 30.0;
  double min_contrast = 0.7;
  double max_contrast = 1.3;
  // Least visible fraction of every pasted part, and placements tried before a part is
  // dropped (--min-visible, --pose-attempts), as in the full-synthetic generator.
  double min_visible_fraction = 0.5;
  int pose_attempts = 5;

  // Background crop and camera effects: BackgroundEffects (background_effects.h).

  bool store_masks = true;

  // A nominal camera (focal length the width, principal point the centre) for the BOP
  // files: pasted patches have no 3D pose, the images no real camera.
  PinholeCamera camera() const;
  // Throws InputError("option --<name>", problem) for the first value out of range.
  void check() const;
};

}  // namespace flexsight

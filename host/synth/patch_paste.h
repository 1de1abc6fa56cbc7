#pragma once
// Pasting one segmented patch into an image: scaled, turned in the image plane,
// mirrored, its brightness and contrast changed, its edge softened inwards over about
// a pixel so that a hard cut-out border does not become a cue the detector learns
// ("Cut, Paste and Learn", Dwibedi et al. 2017, blends the pasted edge for that reason).
#include <opencv2/core.hpp>

#include "host/synth/patch_library.h"

namespace flexsight {

struct PatchPlacement {
  cv::Point2d centre;         // where the patch's box centre lands, image pixels
  double scale = 1.0;         // patch pixels to image pixels
  double angle_degrees = 0;   // counter-clockwise in the image
  bool mirror = false;        // mirrored left-right before turning
  double gain = 1.0;          // contrast: colour' = gain * (colour - 128) + 128 + offset
  double offset = 0.0;        // brightness, grey levels
};

struct PlacedPatch {
  cv::Mat rgb;    // CV_8UC3, the image's size: the transformed patch (0 outside it)
  cv::Mat alpha;  // CV_32FC1, the image's size: the softened coverage, 0..1
  cv::Mat mask;   // CV_8UC1, the image's size: 255 where the transformed mask is (the
                  // annotation; coverage above one half)
};

// The patch transformed into an image of `size`; parts that leave the image are cut.
PlacedPatch place_patch(const Patch& patch, const PatchPlacement& placement, cv::Size size);

// Blends the placed patch over `image` (CV_8UC3) by its alpha.
void paste_patch(cv::Mat& image, const PlacedPatch& placed);

}  // namespace flexsight

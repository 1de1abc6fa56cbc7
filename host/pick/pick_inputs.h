#pragma once
// The files of one pick read and checked before any work, as `flexsight pick` and
// `flexsight serve` both take them: the pair, its calibration brought to the pair's size,
// the left view without the pattern, and detection tiles that fit.
#include <opencv2/core.hpp>
#include <string>

#include "host/geometry/stereo_camera.h"
#include "host/io/image_io.h"

namespace flexsight {

struct PickInputFiles {
  std::string left, right, calib;
  std::string passive_left;  // empty: none
};

struct PickInputImages {
  StereoPair pair;    // RGB8, one size
  StereoCamera rig;   // the calibration at the pair's size
  cv::Mat passive;    // RGB8 at the pair's size; empty without one
};

// Reads `files` in that order; InputError naming the file (or --tile) for an unreadable
// image, views of two sizes, a calibration that does not fit, a passive view of another
// size than the pair, or `detection_tile` (> 0) tiles larger than the left image.
PickInputImages read_pick_inputs(const PickInputFiles& files, int detection_tile);

}  // namespace flexsight

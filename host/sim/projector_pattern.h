#pragma once
// The dot projector as a third camera for calib.txt (host/io/calibration.h): its
// pinhole intrinsics, pose and the pattern image, so that a decoder can read the
// projector's light as a view of its own (docs/projector.md).
//
// The pattern image is a pinhole view of the dot field at the left camera's focal length
// (the projector's pixels as wide as the camera's), just large enough for the field of
// view, principal point at its centre. Each pixel holds the dots' light in the direction
// of its centre, the dot widened by the pixel's footprint as the renderer does
// (dot_projector.h), 255 for an isolated dot's centre, clipped where dots overlap.
#include <opencv2/core.hpp>
#include <string>

#include "host/geometry/stereo_rig.h"
#include "host/io/calibration.h"
#include "host/sim/dot_projector.h"

namespace flexsight {

// The file name synth bin gives the pattern beside calib.txt.
inline constexpr const char* kProjectorPatternFile = "projector_pattern.png";

// The projector of `rig` with the field of `settings`; its pattern named kProjectorPatternFile.
ProjectorCalib projector_calib(const StereoRig& rig, const ProjectorSettings& settings);

// The pattern image (CV_8UC1, projector.width x projector.height).
cv::Mat render_pattern_image(const DotPattern& pattern, const ProjectorCalib& projector);

}  // namespace flexsight

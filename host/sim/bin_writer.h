#pragma once
// One bin's folder: a MiddEval3 stereo scene that `flexsight eval` reads, and the left
// view as a BOP scene folder that the detection and pose evaluators read.
//
//   calib.txt                     cam0, cam1, doffs, baseline, width, height, ndisp, and
//                                 the projector (proj*, host/io/calibration.h)
//   projector_pattern.png         the projector's pattern image (projector_pattern.h)
//   im0.png, im1.png              with the projector's dots
//   im0_passive.png, im1_passive.png   room light only
//   disp0GT.pfm, disp1GT.pfm      disparities (+inf where no surface)
//   mask0nocc.png                 255 where the left pixel's point is seen by both cameras
//   scene_camera.json, scene_gt.json, scene_gt_info.json
//   rgb/ (im0_passive), depth/ (16-bit, 0.1 mm), mask/, mask_visib/   image id = bin index
#include <string>

#include "host/sim/bin_scene.h"

namespace flexsight {

// Writes everything into `folder` (which must exist and be empty: the caller's staging
// folder). The BOP files go through the project's BOP writer.
void write_bin_folder(const std::string& folder, const StereoRig& rig, const BinViews& views);

}  // namespace flexsight

#pragma once
// A sensor plan: the figures of `flexsight sensor-plan` for one rig and working volume
// (coverage, depth resolution, disparity range, and the conditions under which the
// paper's "0.3 mm at the farthest distance" holds). Pure computation; plan_report.h
// prints it.
#include <optional>
#include <string>

#include "host/sensor/sensor_geometry.h"
#include "host/sensor/volume_coverage.h"

namespace flexsight {

struct SensorPlanInputs {
  double baseline_mm = StereoRigSettings().baseline_mm;
  int width = 4000, height = 3000;  // 12 MP
  // Unset: the largest focal length at which the volume fits both images (fitting_focal).
  std::optional<double> focal_px;
  // Unset: the doffs that centres the volume in both images (centring_doffs).
  std::optional<double> doffs_px;
  double projector_hfov_deg = 35.0, projector_vfov_deg = 35.0;
  double projector_offset_mm = 0.0;  // from the middle of the baseline, along x
  WorkingVolume volume;
  // The paper does not name its sensor; 1.55 um is the pixel of the 12 MP Sony sensors
  // sold for the Jetson TX1's MIPI CSI-2 (IMX377, IMX477). It only turns px into mm.
  double pixel_um = 1.55;
  // The matcher's disparity step: 1/16 px, the 4-bit sub-pixel disparity of OpenCV's
  // SGBM/BM (the project's peer matchers). PPMS writes float disparities from slanted
  // planes, so it has no quantisation step; its sub-pixel precision is not measured.
  double subpixel_px = 1.0 / 16.0;
  double target_dz_mm = 0.3;  // the paper's figure at the far plane
  double grid_mm = 10.0;      // coverage sampling step
};

struct SensorPlan {
  SensorPlanInputs inputs;
  StereoRig rig;                 // focal length and doffs resolved
  bool focal_fitted = false;     // whether the focal length is fitting_focal's
  bool doffs_centred = false;    // whether doffs is centring_doffs'
  double fitting_focal_px = 0.0;
  double hfov_deg = 0.0, vfov_deg = 0.0, focal_mm = 0.0;

  // Depth resolution dZ = Z^2 delta_d / (f B) at the near and far planes.
  double dz_near_mm = 0.0, dz_far_mm = 0.0;
  // Lateral size of a pixel (Z / f) at the near and far planes.
  double pixel_near_mm = 0.0, pixel_far_mm = 0.0;

  // Disparities over the volume (they depend on z only: largest at the near plane):
  // f B / Z, and with doffs f B / Z - doffs (what the rectified images show).
  double raw_disparity_near = 0.0, raw_disparity_far = 0.0;
  double disparity_near = 0.0, disparity_far = 0.0;
  // The matcher searches [0, ndisp): its ndisp for the volume, once the pair is shifted
  // so that the far plane lands at disparity >= 0 (shift = floor(disparity_far)).
  int ndisp = 0;
  int matcher_shift_px = 0;

  // The paper's figure: what makes dZ = target at the far plane.
  double subpixel_for_target = 0.0;      // at this focal length
  double focal_for_target_px = 0.0;      // at this sub-pixel step
  double focal_for_target_1px = 0.0;     // at whole-pixel disparities
  double focal_for_lateral_target = 0.0; // where a pixel covers target mm at the far plane
  double subpixel_for_target_at_lateral = 0.0;  // the step that gives dZ = target there

  VolumeCoverage coverage;
};

// Resolves the focal length and doffs, then computes every figure. Inputs are taken as
// checked (positive sizes, fields of view in (0, 180), volume in front of the rig).
SensorPlan make_sensor_plan(const SensorPlanInputs& inputs);

double px_to_mm(double px, double pixel_um);

}  // namespace flexsight

#include "host/sensor/sensor_plan.h"

#include <cmath>

namespace flexsight {

double px_to_mm(double px, double pixel_um) { return px * pixel_um / 1000.0; }

SensorPlan make_sensor_plan(const SensorPlanInputs& in) {
  SensorPlan plan;
  plan.inputs = in;
  const WorkingVolume& vol = in.volume;
  plan.fitting_focal_px = fitting_focal(in.baseline_mm, vol, in.width, in.height);

  plan.focal_fitted = !in.focal_px.has_value();
  const double focal_px = in.focal_px.value_or(plan.fitting_focal_px);
  plan.doffs_centred = !in.doffs_px.has_value();
  const double doffs_px = in.doffs_px ? *in.doffs_px : centring_doffs(focal_px, in.baseline_mm, vol);
  plan.rig = make_centred_stereo_rig(in.baseline_mm, in.width, in.height, focal_px, doffs_px,
                                     {in.projector_offset_mm, in.projector_hfov_deg, in.projector_vfov_deg});
  const StereoRig& rig = plan.rig;

  plan.hfov_deg = hfov_from_focal(rig.focal(), in.width);
  plan.vfov_deg = hfov_from_focal(rig.focal(), in.height);
  plan.focal_mm = px_to_mm(rig.focal(), in.pixel_um);

  const double zn = vol.near_z(), zf = vol.far_z();
  plan.dz_near_mm = depth_step(zn, rig.focal(), in.baseline_mm, in.subpixel_px);
  plan.dz_far_mm = depth_step(zf, rig.focal(), in.baseline_mm, in.subpixel_px);
  plan.pixel_near_mm = zn / rig.focal();
  plan.pixel_far_mm = zf / rig.focal();

  plan.raw_disparity_near = rig.focal() * in.baseline_mm / zn;
  plan.raw_disparity_far = rig.focal() * in.baseline_mm / zf;
  plan.disparity_near = rig.disparity(zn);
  plan.disparity_far = rig.disparity(zf);
  plan.matcher_shift_px = static_cast<int>(std::floor(plan.disparity_far));
  plan.ndisp = static_cast<int>(std::ceil(plan.disparity_near - plan.matcher_shift_px)) + 1;

  const double target = in.target_dz_mm;
  plan.subpixel_for_target = subpixel_for_depth_step(zf, target, rig.focal(), in.baseline_mm);
  plan.focal_for_target_px = focal_for_depth_step(zf, target, in.baseline_mm, in.subpixel_px);
  plan.focal_for_target_1px = focal_for_depth_step(zf, target, in.baseline_mm, 1.0);
  plan.focal_for_lateral_target = zf / target;
  plan.subpixel_for_target_at_lateral =
      subpixel_for_depth_step(zf, target, plan.focal_for_lateral_target, in.baseline_mm);

  plan.coverage = measure_coverage(rig, vol, in.grid_mm);
  return plan;
}

}  // namespace flexsight

#pragma once
// The geometry of a stereo sensor with a pattern projector (the FlexSight C1 of the
// paper, Sec. III, Fig. 3): two cameras on the x axis, a baseline apart, and a projector
// between them, all looking along +z; and the box they must see. Units: mm and pixels.
//
// The rig itself (host/geometry/stereo_rig.h, make_centred_stereo_rig) is modelled as
// the matcher sees it: rectified and parallel, with Middlebury's doffs. A converging
// (toed-in) rig becomes exactly this after rectification, up to the warp of the image
// borders, and disparities exist only on rectified images; so depth resolution and
// disparity range are those of this model whatever the mechanical toe-in.
#include <Eigen/Core>

#include "host/geometry/stereo_rig.h"

namespace flexsight {

// The planner's view of a rig camera (StereoRig: intrinsics, and its centre at x =
// centre_x on the baseline, in the rig frame): the image spans [0, width] x [0, height]
// (pixel corners). The image position of rig-frame point p; false (and u, v untouched)
// when p is not in front (z <= 0).
bool project_from(const PinholeCamera& camera, double centre_x, const Eigen::Vector3d& p, double& u,
                  double& v);
// Whether p lands in the image; the border counts (a volume that fits exactly is seen).
bool camera_sees(const PinholeCamera& camera, double centre_x, const Eigen::Vector3d& p);

// f = (width / 2) / tan(hfov / 2), and back.
double focal_from_hfov(double hfov_deg, int width);
double hfov_from_focal(double focal_px, int width);

// The depth step that one disparity step delta_d makes at depth z: differentiating
// Z = f B / (d + doffs) gives dZ = Z^2 delta_d / (f B) (doffs drops out).
double depth_step(double z, double focal_px, double baseline_mm, double subpixel_px);
// The focal length (px) at which depth_step(z, ...) == step_mm, and the disparity step
// at which it does for a given focal length: the same formula solved for f or delta_d.
double focal_for_depth_step(double z, double step_mm, double baseline_mm, double subpixel_px);
double subpixel_for_depth_step(double z, double step_mm, double focal_px, double baseline_mm);

}  // namespace flexsight

#pragma once
// The one stereo rig: two parallel cameras of the same focal length, the right one
// `baseline_mm` to the right of the left one, a pattern projector on the baseline, and
// the working volume they must see. The pair is rectified by construction (same
// rotation, same fy, cy): a point's rows agree in both views and its disparity is
// f B / Z - doffs, Middlebury 2014's calib.txt convention (Z = f B / (d + doffs)).
// The simulator renders with it, the sensor planner measures it, the cloud, pick and
// pose commands meet it as the StereoCamera (Q) of a calibration file.
//
// The doffs rule. The principal points are shifted apart (right.cx = left.cx + doffs):
// parallel cameras 500 mm apart would see the volume 40 % of an image width apart at
// 1.25 m, so with centred principal points much of each view would show what the other
// cannot see. A converging (toed-in) rig becomes exactly this after rectification, so a
// positive doffs is the rectified form of a rig aimed at the volume. Two construction
// functions choose f and doffs, each from the volume's corners:
// - make_stereo_rig (the bin simulator): f the largest focal length that keeps the
//   volume inside both views with a margin of kSimMargin of the image on each side
//   (floored to 1/1000 px); doffs = floor(f B / (far face + kSimFarReserveMm)), so that
//   the bin floor on the far face and the table just below it keep positive
//   disparities; principal points at the image centre (pixel centres: (W - 1) / 2)
//   moved by -doffs/2 and +doffs/2.
// - make_centred_stereo_rig (the sensor planner): doffs = centring_doffs, which centres
//   the volume's horizontal extent in both images with no margin, and f fitting_focal
//   unless given; principal points at the image centre (pixel corners: W / 2) moved by
//   -doffs/2 and +doffs/2.
// Both keep the numbers their callers have always had (recorded output hashes).
#include <Eigen/Core>
#include <string>

#include "host/geometry/pinhole_camera.h"
#include "host/geometry/pose.h"
#include "host/geometry/stereo_camera.h"

namespace flexsight {

// The working volume: an axis-aligned box centred on the rig's middle axis at
// `distance` from the baseline's middle. width along x (the baseline), height along y,
// depth along the viewing direction. Units: mm.
struct WorkingVolume {
  double width = 600.0, height = 400.0, depth = 400.0;
  double distance = 1250.0;

  double near_z() const { return distance - depth / 2.0; }
  double far_z() const { return distance + depth / 2.0; }
  double min_x() const { return -width / 2.0; }
  double max_x() const { return width / 2.0; }
  double min_y() const { return -height / 2.0; }
  double max_y() const { return height / 2.0; }
  // Corner i in the rig frame: bit 0 picks max x, bit 1 max y, bit 2 the far plane.
  Eigen::Vector3d corner(int i) const;
  double volume_mm3() const { return width * height * depth; }
};

// What a rig is built from; the project's rig defaults are written here and only here.
struct StereoRigSettings {
  int width = 1280, height = 960;  // pixels, both views
  double baseline_mm = 500.0;      // between the camera centres, along x
  WorkingVolume volume;
  // Focal length in pixels; 0 takes the largest that keeps the whole volume inside both
  // views (by the construction function's rule).
  double focal_px = 0.0;
};

// The pattern projector: a symmetric frustum looking along the cameras' axis, its apex
// `centre_x` from the middle of the baseline along x.
struct Projector {
  double centre_x = 0.0;
  double hfov_deg = 35.0, vfov_deg = 35.0;
  // Whether rig-frame point p lies inside the frustum; a point exactly on it counts.
  bool sees(const Eigen::Vector3d& p) const;
};

// Frames: the rig frame has its origin at the middle of the baseline, x along it, z
// along the viewing direction; the left camera sits at x = -B/2, the right at +B/2. The
// cameras use OpenCV's frame (x right, y down, z forward). The simulator's "world" is
// the bin's frame (origin at the middle of the bin floor's top surface, z up), tied to
// the left camera by R_cw, t_cw.
struct StereoRig {
  PinholeCamera left, right;  // same f and cy; right.cx - left.cx = doffs
  double baseline_mm = 0.0;
  double doffs = 0.0;  // px, Middlebury's doffs
  int ndisp = 0;       // covers the disparities of the whole working volume (0: not planned)
  Projector projector;
  // x_left = R_cw x_world + t_cw. The right camera's frame is the left one's moved by
  // +baseline along x: x_right = x_left - (baseline, 0, 0).
  Eigen::Matrix3d R_cw = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_cw = Eigen::Vector3d::Zero();

  double focal() const { return left.fx; }
  // The camera centres' x in the rig frame.
  double left_centre_x() const { return -baseline_mm / 2.0; }
  double right_centre_x() const { return baseline_mm / 2.0; }
  // The projector's apex in the left camera's frame.
  Eigen::Vector3d projector_in_left() const {
    return Eigen::Vector3d(projector.centre_x - left_centre_x(), 0.0, 0.0);
  }
  // A model's world pose seen from the left or the right camera.
  Pose to_left(const Pose& world) const;
  Pose to_right(const Pose& world) const;
  // A world point in the left camera's frame.
  Eigen::Vector3d left_point(const Eigen::Vector3d& world) const { return R_cw * world + t_cw; }
  // The Middlebury disparity of a point at depth z (mm): f B / z - doffs.
  double disparity(double z) const { return left.fx * baseline_mm / z - doffs; }
  // The rig as the reprojection matrix Q of a calibration file (mm).
  StereoCamera stereo_camera() const;
  // calib.txt (MiddEval3): cam0, cam1, doffs, baseline, width, height, ndisp.
  std::string calib_text() const;
};

// The rig a calibration file's Q describes, for images of width x height: f = Q[2][3],
// left principal point (-Q[0][3], -Q[1][3]), baseline 1 / Q[3][2] (in camera.unit) and
// doffs Q[3][3] / Q[3][2] (px). The inverse of StereoRig::stereo_camera.
StereoRig stereo_rig_from(const StereoCamera& camera, int width, int height);

// The bin simulator's rule (see the top of this file). Throws InputError naming the
// option (--size, --baseline, --distance, --volume, --focal) for a size or length that
// is not positive or not finite, a volume that reaches the cameras, or a focal length
// with which the volume does not fit in both views.
StereoRig make_stereo_rig(const StereoRigSettings& settings);
// The simulator's share of the image kept free on each side when it chooses f, and the
// depth beyond the volume's far face whose disparity its doffs makes zero.
constexpr double kSimMargin = 0.04;
constexpr double kSimFarReserveMm = 40.0;

// The sensor planner's rule (see the top of this file), for a focal length and doffs
// already chosen (fitting_focal, centring_doffs or the user's). Inputs are taken as checked.
StereoRig make_centred_stereo_rig(double baseline_mm, int width, int height, double focal_px,
                                  double doffs_px, const Projector& projector);

// The doffs that centres the volume's horizontal extent in each camera's image (the
// extent of (x - centre) / z over the box's corners; the volume is symmetric about the
// middle axis, so one doffs centres it in both): the best use of the pixels, and what a
// rig aimed at the volume gives after rectification. Scales with the focal length.
double centring_doffs(double focal_px, double baseline_mm, const WorkingVolume& volume);

// The largest focal length at which the whole volume fits in both images with the
// centring doffs: min(width / horizontal tangent extent, (height / 2) / max |y / z|).
double fitting_focal(double baseline_mm, const WorkingVolume& volume, int width, int height);

}  // namespace flexsight

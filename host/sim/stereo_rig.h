#pragma once
// The stereo camera of the bin simulator: two parallel cameras of the same focal length,
// the right one `baseline` mm to the right of the left one, both looking straight down
// at a working volume whose centroid lies `distance` mm away. The pair is rectified by
// construction (same rotation, same fy, cy): a point's rows agree in both views and its
// disparity is f B / Z - doffs, as the Middlebury 2014 calib.txt describes.
//
// The principal points are shifted apart (cam1's cx = cam0's cx + doffs): parallel
// cameras 500 mm apart would see the volume 40 % of an image width apart at 1.25 m, so
// with centred principal points much of each view would show what the other cannot
// see. Shifting them keeps the volume in the middle of both views and the disparities of
// the volume small and positive (doffs is chosen just beyond the far end of the volume).
#include <Eigen/Core>
#include <string>

#include "host/render/raycaster.h"

namespace flexsight {

struct StereoRigSettings {
  int width = 1280, height = 960;  // pixels, both views
  double baseline_mm = 500.0;      // between the camera centres, along x
  double distance_mm = 1250.0;     // from the baseline's middle to the volume's centroid
  // The working volume: x along the baseline, y across it, z along the viewing direction.
  double volume_x_mm = 600.0, volume_y_mm = 400.0, volume_z_mm = 400.0;
  // Focal length in pixels; 0 takes the largest that keeps the whole volume inside both
  // views with a margin of 4 % of the image on each side.
  double focal_px = 0.0;
};

// Frames: the "world" is the bin's frame, origin at the middle of the bin floor's top
// surface (the bottom face of the working volume), x along the baseline, z up. The
// cameras use OpenCV's frame (x right, y down, z forward = down into the bin).
struct StereoRig {
  PinholeCamera left, right;  // same f and cy; right.cx = left.cx + doffs
  double baseline_mm = 0.0;
  double doffs = 0.0;
  int ndisp = 0;  // covers the disparities of the whole working volume
  // x_left = R_cw x_world + t_cw. The right camera's frame is the left one's moved by
  // +baseline along x: x_right = x_left - (baseline, 0, 0).
  Eigen::Matrix3d R_cw = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_cw = Eigen::Vector3d::Zero();

  double focal() const { return left.fx; }
  // A model's world pose seen from the left or the right camera.
  Pose to_left(const Pose& world) const;
  Pose to_right(const Pose& world) const;
  // A world point in the left camera's frame.
  Eigen::Vector3d left_point(const Eigen::Vector3d& world) const { return R_cw * world + t_cw; }
  // The Middlebury disparity of a point at depth z (mm): f B / z - doffs.
  double disparity(double z) const { return left.fx * baseline_mm / z - doffs; }
  // calib.txt (MiddEval3): cam0, cam1, doffs, baseline, width, height, ndisp.
  std::string calib_text() const;
};

// Throws InputError naming the option (--size, --baseline, --distance, --volume,
// --focal) for a size or length that is not positive or not finite, a volume that
// reaches the cameras, or a focal length with which the volume does not fit in both views.
StereoRig make_stereo_rig(const StereoRigSettings& settings);

}  // namespace flexsight

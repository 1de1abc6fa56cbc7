#pragma once
// The one camera type: pinhole intrinsics and an image size. The renderer casts its rays
// through it, the stereo rig (stereo_rig.h) holds two, the pose estimator projects with it.
//
// Frames follow OpenCV: the camera looks along +z, x to the right, y down, in mm. A
// pixel (u, v) is the point u, v of the image plane (pixel centres on integer
// coordinates, as cv::projectPoints).
#include <Eigen/Core>

namespace flexsight {

struct PinholeCamera {
  double fx = 600.0, fy = 600.0;  // focal lengths in pixels
  double cx = 319.5, cy = 239.5;  // principal point in pixels
  int width = 640, height = 480;
  // Throws InputError ("camera: ...") for a size or focal length that is not positive
  // or not finite.
  void check() const;
  // The pixel coordinates where camera-frame point p appears (p.z > 0).
  Eigen::Vector2d project(const Eigen::Vector3d& p) const;
};

// A camera of `width` x `height` pixels, focal length `focal` pixels on both axes, whose
// principal point is the image's centre.
PinholeCamera centred_camera(int width, int height, double focal);

}  // namespace flexsight

#pragma once
// The rectified stereo rig as one reprojection matrix Q, the form cv::stereoRectify
// writes: [X Y Z W]^T = Q [x y d 1]^T for left-image pixel (x, y) with disparity d,
// and the 3D point is (X/W, Y/W, Z/W) in the left camera frame. Middlebury, KITTI and
// OpenCV calibration files all map onto it, so the cloud code has one camera model.
#include <Eigen/Core>
#include <string>

namespace flexsight {

struct StereoCamera {
  Eigen::Matrix4d Q = Eigen::Matrix4d::Identity();
  // Size of the images the calibration is for (0 when the file does not say).
  int width = 0;
  int height = 0;
  // Length unit of Q's translation (the baseline): points come out in it.
  std::string unit = "mm";
  double metres_per_unit = 1e-3;
  std::string source;  // the file it was read from, for messages

  // Depth Z of disparity d (in `unit`); NaN where d + doffs <= 0 (at or beyond infinity).
  double depth(double disparity) const;
  // Point of pixel (x, y) with disparity d; false (and nothing written) behind infinity.
  bool point(double x, double y, double disparity, Eigen::Vector3d& out) const;
  // Unit normal, facing the camera, of the scene plane that a disparity plane
  // d = a x + b y + c maps to. A plane of (x, y, d) space is a plane of projective
  // 3-space, so it maps through Q exactly: pi' = Q^-T (a, b, -1, c).
  // `plane_map` is Q^-T (plane_map()), computed once per image by the caller.
  Eigen::Matrix4d plane_map() const;
  static bool plane_normal(const Eigen::Matrix4d& plane_map, double a, double b, double c,
                           const Eigen::Vector3d& point_on_plane, Eigen::Vector3d& out);

  // The same rig for images resized by a uniform factor (MiddEval3 F -> Q, a fixture
  // downscaled from a scene): pixels and disparities scale together, Q' = Q diag(1/s,1/s,1/s,1).
  // Throws InputError naming `source` when the factor differs between the axes by more
  // than a pixel, since then the images are not this rig's.
  StereoCamera resized_to(int image_width, int image_height) const;
};

// Middlebury 2014 calib.txt (mm), KITTI 2012/2015 calib (m), or OpenCV's stereo
// calibration output (YAML/XML with Q from cv::stereoRectify, optionally "unit"), told
// apart by content. Throws InputError naming the file for a missing or malformed file.
StereoCamera read_stereo_camera(const std::string& path);

// The three formats, for callers that know which one they hold.
StereoCamera read_middlebury_camera(const std::string& path);
StereoCamera read_kitti_camera(const std::string& path);
StereoCamera read_opencv_camera(const std::string& path);

// Q for a rectified pair with focal length f (px), left principal point (cx, cy),
// right principal point x cx_right and baseline (in the output unit).
Eigen::Matrix4d reprojection_matrix(double f, double cx, double cy, double cx_right,
                                    double baseline);

}  // namespace flexsight

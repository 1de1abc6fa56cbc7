#pragma once
// The plane a bin's parts lie on, fitted to a measured depth map. The widest plane that
// faces the camera is found by RANSAC; the floor is then the highest level parallel to it
// that still holds a good share of the pixels: a bin standing on a table shows the table
// as the widest plane, its own floor a few millimetres above it.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "host/geometry/pinhole_camera.h"

namespace flexsight {

struct FloorPlaneOptions {
  // Pixels sampled on a grid of this step (pixels) for the fit; 0 picks it from the
  // image size (about 300 x 240 samples).
  int sample_step = 0;
  // RANSAC hypotheses drawn (three sampled points each, a fixed seed: the fit is
  // reproducible).
  int iterations = 300;
  // A point lies on a plane when nearer than this fraction of the median depth (3 mm at
  // 1.25 m: stereo depth at that range is about 1 mm off).
  double inlier_ratio = 0.0025;
  // Planes tilted more than this from the optical axis are no floor (degrees): walls.
  double max_tilt_deg = 60.0;
  // The floor lies at most this far (mm) above the widest plane (the bin's bottom
  // thickness over a table; a wall's rim lies higher).
  double max_rise_mm = 40.0;
  // A level holds the floor when at least this share of the sampled points lie on it.
  double min_share = 0.05;
  void check() const;
};

struct FloorPlane {
  // n . p + d is a point's height above the floor (mm); n is unit and points at the
  // camera.
  Eigen::Vector3d normal = Eigen::Vector3d(0.0, 0.0, -1.0);
  double offset = 0.0;
  bool found = false;       // false: too few measured pixels or no plane facing the camera
  double inlier_share = 0;  // of the sampled points, those on the floor
  double height(const Eigen::Vector3d& p) const { return normal.dot(p) + offset; }
};

// The camera-frame point (mm) of pixel (u, v) at depth z.
inline Eigen::Vector3d back_project(const PinholeCamera& camera, double u, double v, double z) {
  return {(u - camera.cx) * z / camera.fx, (v - camera.cy) * z / camera.fy, z};
}

// `depth_mm`: CV_32FC1, 0 or not finite where unknown.
FloorPlane fit_floor_plane(const cv::Mat& depth_mm, const PinholeCamera& camera,
                           const FloorPlaneOptions& options = FloorPlaneOptions());

}  // namespace flexsight

#pragma once
// The projector seen from the left camera of a rectified pair: where a left pixel at a
// disparity falls in the projector's pattern, and the pattern resampled along the
// camera's rows (the "virtual view") that the decoder compares windows against.
//
// The decoder needs a projector whose rows are the cameras' rows (projR the identity,
// projt along the baseline): then a left pixel (u, v) at disparity d meets the pattern on
// the row vp(v) whatever d, at the camera-equivalent column
//   w = u + tx (d + doffs) / B,   up = fpx / f (w - cx) + cxp,   vp = fpy / f (v - cy) + cyp
// (tx = projt's x, B the baseline): the projector is a third rectified camera, and the
// search for d is a search along the row, as in stereo.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "host/io/calibration.h"

namespace flexsight {

// The left camera of a calib.txt with what turns disparity into depth.
struct LeftCamera {
  double f = 0, cx = 0, cy = 0, baseline_mm = 0, doffs = 0;
  int width = 0, height = 0, ndisp = 0;
  explicit LeftCamera(const MiddleburyCalib& calib);
  // The point of pixel (u, v) at disparity d in the left camera's frame (mm).
  Eigen::Vector3d point(double u, double v, double d) const;
};

// Where a left-camera point lands in the pattern (px); NaN when behind the projector.
Eigen::Vector2d project_to_pattern(const ProjectorCalib& projector, const Eigen::Vector3d& point);

// The pattern image at projector.pattern_path as CV_32FC1 (0..1); InputError naming the
// file when it is missing, unreadable or not projwidth x projheight.
cv::Mat load_pattern(const ProjectorCalib& projector);

// Throws InputError naming `source` when the projector is not rectified with the cameras
// (projR not the identity, projt off the baseline) or sits at the left camera (tx = 0):
// the decoder's search needs a row.
void require_rectified_projector(const ProjectorCalib& projector, const std::string& source);

// The pattern resampled on the camera's rows, two samples per camera pixel along them:
// sample (v, j) is the pattern at camera-equivalent column w = w0 + j / 2 on row v.
struct VirtualView {
  cv::Mat samples;  // CV_32FC1, camera height x columns; 0 outside the pattern
  double w0 = 0;
  // The sample column of camera-equivalent column w (rounded).
  int column(double w) const { return int(std::lround(2.0 * (w - w0))); }
};
VirtualView make_virtual_view(const LeftCamera& camera, const ProjectorCalib& projector,
                              const cv::Mat& pattern);

}  // namespace flexsight

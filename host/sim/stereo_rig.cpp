#include "host/sim/stereo_rig.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

// The share of the image kept free on each side when the focal length is chosen.
constexpr double kMargin = 0.04;
// doffs is the disparity offset of a depth this far beyond the volume's far face: the
// bin floor lies on that face and the table under the bin a little below it, and both
// must keep positive disparities.
constexpr double kFarReserveMm = 40.0;

void require_positive(double value, const std::string& option) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InputError("option " + option, "must be a positive number, got " + std::to_string(value));
  }
}

// The volume's eight corners in the left camera's frame.
std::vector<Eigen::Vector3d> volume_corners(const StereoRigSettings& s) {
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back(0.5 * s.baseline_mm + ((i & 1) ? 0.5 : -0.5) * s.volume_x_mm,
                         ((i & 2) ? 0.5 : -0.5) * s.volume_y_mm,
                         s.distance_mm + ((i & 4) ? 0.5 : -0.5) * s.volume_z_mm);
  }
  return corners;
}

}  // namespace

Pose StereoRig::to_left(const Pose& world) const {
  Pose pose;
  pose.R = R_cw * world.R;
  pose.t = R_cw * world.t + t_cw;
  return pose;
}

Pose StereoRig::to_right(const Pose& world) const {
  Pose pose = to_left(world);
  pose.t.x() -= baseline_mm;
  return pose;
}

std::string StereoRig::calib_text() const {
  char text[512];
  std::snprintf(text, sizeof text,
                "cam0=[%.3f 0 %.3f; 0 %.3f %.3f; 0 0 1]\n"
                "cam1=[%.3f 0 %.3f; 0 %.3f %.3f; 0 0 1]\n"
                "doffs=%.3f\nbaseline=%.1f\nwidth=%d\nheight=%d\nndisp=%d\n",
                left.fx, left.cx, left.fy, left.cy, right.fx, right.cx, right.fy, right.cy, doffs,
                baseline_mm, left.width, left.height, ndisp);
  return text;
}

StereoRig make_stereo_rig(const StereoRigSettings& s) {
  if (s.width < 8 || s.height < 8) throw InputError("option --size", "at least 8x8 pixels");
  require_positive(s.baseline_mm, "--baseline");
  require_positive(s.distance_mm, "--distance");
  require_positive(s.volume_x_mm, "--volume");
  require_positive(s.volume_y_mm, "--volume");
  require_positive(s.volume_z_mm, "--volume");
  if (!std::isfinite(s.focal_px) || s.focal_px < 0.0) {
    throw InputError("option --focal", "must be positive (or 0 for automatic)");
  }
  const double near = s.distance_mm - 0.5 * s.volume_z_mm;
  if (near < 100.0) {
    throw InputError("option --distance",
                     "the working volume's near face is " + std::to_string(near) +
                         " mm from the cameras; it must be at least 100 mm away");
  }
  const double far_doffs = s.distance_mm + 0.5 * s.volume_z_mm + kFarReserveMm;
  const double B = s.baseline_mm;
  // Image coordinates relative to the centre, divided by f: linear in f once doffs is
  // taken as f B / far_doffs, so the largest focal length that fits is one division.
  const double kd = B / far_doffs;
  double max_u = 0.0, max_v = 0.0;
  for (const Eigen::Vector3d& p : volume_corners(s)) {
    max_u = std::max({max_u, std::abs(p.x() / p.z() - 0.5 * kd),
                      std::abs((p.x() - B) / p.z() + 0.5 * kd)});
    max_v = std::max(max_v, std::abs(p.y() / p.z()));
  }
  double f = s.focal_px;
  if (f == 0.0) {
    f = std::min((1.0 - 2.0 * kMargin) * 0.5 * s.width / max_u,
                 (1.0 - 2.0 * kMargin) * 0.5 * s.height / max_v);
    f = std::floor(f * 1000.0) / 1000.0;
  }

  StereoRig rig;
  rig.baseline_mm = B;
  rig.doffs = std::floor(f * B / far_doffs);
  rig.ndisp = static_cast<int>(std::ceil(f * B / near - rig.doffs)) + 2;
  const double cx = 0.5 * (s.width - 1), cy = 0.5 * (s.height - 1);
  for (PinholeCamera* camera : {&rig.left, &rig.right}) {
    camera->fx = camera->fy = f;
    camera->cy = cy;
    camera->width = s.width;
    camera->height = s.height;
  }
  // Symmetric: the volume's centroid lies as far right of the middle in the left view as
  // left of it in the right view.
  rig.left.cx = cx - 0.5 * rig.doffs;
  rig.right.cx = rig.left.cx + rig.doffs;
  rig.R_cw = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  rig.t_cw = Eigen::Vector3d(0.5 * B, 0.0, s.distance_mm + 0.5 * s.volume_z_mm);

  // Every corner of the volume inside both views (pixel centres 0..W-1).
  for (const Eigen::Vector3d& p : volume_corners(s)) {
    const Eigen::Vector2d a = rig.left.project(p);
    const Eigen::Vector2d b = rig.right.project(p - Eigen::Vector3d(B, 0.0, 0.0));
    for (const Eigen::Vector2d& q : {a, b}) {
      if (q.x() < 0.0 || q.y() < 0.0 || q.x() > s.width - 1.0 || q.y() > s.height - 1.0) {
        char text[256];
        std::snprintf(text, sizeof text,
                      "with focal length %.1f px the %gx%gx%g mm working volume does not fit in "
                      "both %dx%d views (a corner falls at pixel %.0f, %.0f); at most %.1f px",
                      f, s.volume_x_mm, s.volume_y_mm, s.volume_z_mm, s.width, s.height, q.x(),
                      q.y(),
                      std::min(0.5 * s.width / max_u, 0.5 * s.height / max_v));
        throw InputError(s.focal_px > 0.0 ? "option --focal" : "option --size", text);
      }
    }
  }
  rig.left.check();
  rig.right.check();
  return rig;
}

}  // namespace flexsight

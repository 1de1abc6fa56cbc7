#include "host/geometry/stereo_rig.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

constexpr double kPi = 3.14159265358979323846;

double radians(double degrees) { return degrees * kPi / 180.0; }

void require_positive(double value, const std::string& option) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InputError("option " + option, "must be a positive number, got " + std::to_string(value));
  }
}

// The volume's eight corners in the left camera's frame.
std::vector<Eigen::Vector3d> volume_corners(const StereoRigSettings& s) {
  std::vector<Eigen::Vector3d> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back(0.5 * s.baseline_mm + ((i & 1) ? 0.5 : -0.5) * s.volume.width,
                         ((i & 2) ? 0.5 : -0.5) * s.volume.height,
                         s.volume.distance + ((i & 4) ? 0.5 : -0.5) * s.volume.depth);
  }
  return corners;
}

// Smallest and largest (x - centre_x) / z over the volume's corners: the horizontal
// extent of the volume in a parallel camera at centre_x, in units of the focal length.
// (x - c) / z is monotone in x and in 1 / z, so the corners bound it.
void tangent_extent(const WorkingVolume& volume, double centre_x, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c = volume.corner(i);
    const double t = (c.x() - centre_x) / c.z();
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
}

}  // namespace

Eigen::Vector3d WorkingVolume::corner(int i) const {
  return {(i & 1) ? max_x() : min_x(), (i & 2) ? max_y() : min_y(), (i & 4) ? far_z() : near_z()};
}

bool Projector::sees(const Eigen::Vector3d& p) const {
  if (!(p.z() > 0.0)) return false;
  // Relative tolerance, as for the cameras: a face exactly on the frustum is lit.
  const double slack = 1e-12;
  return std::abs(p.x() - centre_x) <= p.z() * (std::tan(radians(hfov_deg / 2.0)) + slack) &&
         std::abs(p.y()) <= p.z() * (std::tan(radians(vfov_deg / 2.0)) + slack);
}

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

StereoCamera StereoRig::stereo_camera() const {
  StereoCamera camera;
  camera.Q = reprojection_matrix(left.fx, left.cx, left.cy, right.cx, baseline_mm);
  camera.width = left.width;
  camera.height = left.height;
  return camera;
}

StereoRig stereo_rig_from(const StereoCamera& camera, int width, int height) {
  const Eigen::Matrix4d& Q = camera.Q;
  StereoRig rig;
  rig.left.fx = rig.left.fy = Q(2, 3);
  rig.left.cx = -Q(0, 3);
  rig.left.cy = -Q(1, 3);
  rig.left.width = width;
  rig.left.height = height;
  rig.baseline_mm = 1.0 / Q(3, 2);
  rig.doffs = Q(3, 3) / Q(3, 2);
  rig.right = rig.left;
  rig.right.cx = rig.left.cx + rig.doffs;
  return rig;
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
  require_positive(s.volume.distance, "--distance");
  require_positive(s.volume.width, "--volume");
  require_positive(s.volume.height, "--volume");
  require_positive(s.volume.depth, "--volume");
  if (!std::isfinite(s.focal_px) || s.focal_px < 0.0) {
    throw InputError("option --focal", "must be positive (or 0 for automatic)");
  }
  const double near = s.volume.distance - 0.5 * s.volume.depth;
  if (near < 100.0) {
    throw InputError("option --distance",
                     "the working volume's near face is " + std::to_string(near) +
                         " mm from the cameras; it must be at least 100 mm away");
  }
  const double far_doffs = s.volume.distance + 0.5 * s.volume.depth + kSimFarReserveMm;
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
    f = std::min((1.0 - 2.0 * kSimMargin) * 0.5 * s.width / max_u,
                 (1.0 - 2.0 * kSimMargin) * 0.5 * s.height / max_v);
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
  rig.t_cw = Eigen::Vector3d(0.5 * B, 0.0, s.volume.distance + 0.5 * s.volume.depth);

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
                      f, s.volume.width, s.volume.height, s.volume.depth, s.width, s.height, q.x(),
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

StereoRig make_centred_stereo_rig(double baseline_mm, int width, int height, double focal_px,
                                  double doffs_px, const Projector& projector) {
  StereoRig rig;
  rig.baseline_mm = baseline_mm;
  rig.doffs = doffs_px;
  rig.projector = projector;
  rig.left = {focal_px, focal_px, width / 2.0 - doffs_px / 2.0, height / 2.0, width, height};
  rig.right = {focal_px, focal_px, width / 2.0 + doffs_px / 2.0, height / 2.0, width, height};
  // The rig frame is the world: x_left = x_rig + (B/2, 0, 0).
  rig.t_cw = Eigen::Vector3d(-rig.left_centre_x(), 0.0, 0.0);
  return rig;
}

double centring_doffs(double focal_px, double baseline_mm, const WorkingVolume& volume) {
  // The left camera's window is centred when cx_left = width / 2 - f * mid_left; the
  // right's likewise; doffs = cx_right - cx_left.
  double lo = 0.0, hi = 0.0;
  tangent_extent(volume, -baseline_mm / 2.0, lo, hi);
  const double mid_left = (lo + hi) / 2.0;
  tangent_extent(volume, baseline_mm / 2.0, lo, hi);
  const double mid_right = (lo + hi) / 2.0;
  return focal_px * (mid_left - mid_right);
}

double fitting_focal(double baseline_mm, const WorkingVolume& volume, int width, int height) {
  double lo = 0.0, hi = 0.0;
  tangent_extent(volume, -baseline_mm / 2.0, lo, hi);  // the right camera's mirrors it
  double max_y_tangent = 0.0;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d c = volume.corner(i);
    max_y_tangent = std::max(max_y_tangent, std::abs(c.y()) / c.z());
  }
  return std::min(width / (hi - lo), (height / 2.0) / max_y_tangent);
}

}  // namespace flexsight

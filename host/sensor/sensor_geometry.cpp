#include "host/sensor/sensor_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace flexsight {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Points on the border of an image count as seen: a volume sized to fit exactly (the
// default focal length) must not lose its corners to rounding.
constexpr double kBorderTolerancePx = 1e-6;

double radians(double degrees) { return degrees * kPi / 180.0; }

// Smallest and largest (x - centre_x) / z over the volume's corners: the horizontal
// extent of the volume in a parallel camera at centre_x, in units of the focal length.
// (x - c) / z is monotone in x and in 1 / z, so the corners bound it.
void tangent_extent(const WorkingVolume& volume, double centre_x, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (int i = 0; i < 8; ++i) {
    const Point3 c = volume.corner(i);
    const double t = (c.x - centre_x) / c.z;
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
}

}  // namespace

Point3 WorkingVolume::corner(int i) const {
  return {(i & 1) ? max_x() : min_x(), (i & 2) ? max_y() : min_y(), (i & 4) ? far_z() : near_z()};
}

bool PinholeCamera::project(const Point3& p, double& u, double& v) const {
  if (!(p.z > 0.0)) return false;
  u = focal_px * (p.x - centre_x) / p.z + cx;
  v = focal_px * p.y / p.z + cy;
  return true;
}

bool PinholeCamera::sees(const Point3& p) const {
  double u = 0.0, v = 0.0;
  if (!project(p, u, v)) return false;
  return u >= -kBorderTolerancePx && u <= width + kBorderTolerancePx && v >= -kBorderTolerancePx &&
         v <= height + kBorderTolerancePx;
}

bool Projector::sees(const Point3& p) const {
  if (!(p.z > 0.0)) return false;
  // Relative tolerance, as for the cameras: a face exactly on the frustum is lit.
  const double slack = 1e-12;
  return std::abs(p.x - centre_x) <= p.z * (std::tan(radians(hfov_deg / 2.0)) + slack) &&
         std::abs(p.y) <= p.z * (std::tan(radians(vfov_deg / 2.0)) + slack);
}

PinholeCamera StereoRig::left() const {
  return {-baseline_mm / 2.0, focal_px, width / 2.0 - doffs_px / 2.0, height / 2.0, width, height};
}

PinholeCamera StereoRig::right() const {
  return {baseline_mm / 2.0, focal_px, width / 2.0 + doffs_px / 2.0, height / 2.0, width, height};
}

double StereoRig::disparity_at(double z) const { return focal_px * baseline_mm / z - doffs_px; }

double focal_from_hfov(double hfov_deg, int width) { return (width / 2.0) / std::tan(radians(hfov_deg / 2.0)); }

double hfov_from_focal(double focal_px, int width) {
  return 2.0 * std::atan((width / 2.0) / focal_px) * 180.0 / kPi;
}

double depth_step(double z, double focal_px, double baseline_mm, double subpixel_px) {
  return z * z * subpixel_px / (focal_px * baseline_mm);
}

double focal_for_depth_step(double z, double step_mm, double baseline_mm, double subpixel_px) {
  return z * z * subpixel_px / (step_mm * baseline_mm);
}

double subpixel_for_depth_step(double z, double step_mm, double focal_px, double baseline_mm) {
  return step_mm * focal_px * baseline_mm / (z * z);
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
    const Point3 c = volume.corner(i);
    max_y_tangent = std::max(max_y_tangent, std::abs(c.y) / c.z);
  }
  return std::min(width / (hi - lo), (height / 2.0) / max_y_tangent);
}

}  // namespace flexsight

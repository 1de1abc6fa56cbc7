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

}  // namespace

bool project_from(const PinholeCamera& camera, double centre_x, const Eigen::Vector3d& p, double& u,
                  double& v) {
  if (!(p.z() > 0.0)) return false;
  const Eigen::Vector2d image = camera.project(Eigen::Vector3d(p.x() - centre_x, p.y(), p.z()));
  u = image.x();
  v = image.y();
  return true;
}

bool camera_sees(const PinholeCamera& camera, double centre_x, const Eigen::Vector3d& p) {
  double u = 0.0, v = 0.0;
  if (!project_from(camera, centre_x, p, u, v)) return false;
  return u >= -kBorderTolerancePx && u <= camera.width + kBorderTolerancePx && v >= -kBorderTolerancePx &&
         v <= camera.height + kBorderTolerancePx;
}

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

}  // namespace flexsight

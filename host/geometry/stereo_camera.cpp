#include "host/geometry/stereo_camera.h"

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <sstream>

#include "host/io/input_error.h"

namespace flexsight {

Eigen::Matrix4d reprojection_matrix(double f, double cx, double cy, double cx_right,
                                    double baseline) {
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  Q(0, 0) = 1;
  Q(0, 3) = -cx;
  Q(1, 1) = 1;
  Q(1, 3) = -cy;
  Q(2, 3) = f;
  // W = (d + doffs) / B with doffs = cx_right - cx, so Z = f B / (d + doffs).
  Q(3, 2) = 1.0 / baseline;
  Q(3, 3) = (cx_right - cx) / baseline;
  return Q;
}

double StereoCamera::depth(double disparity) const {
  const double w = Q(3, 2) * disparity + Q(3, 3);
  const double z = Q(2, 2) * disparity + Q(2, 3);
  if (!(w > 0) || !std::isfinite(disparity)) return std::numeric_limits<double>::quiet_NaN();
  return z / w;
}

bool StereoCamera::point(double x, double y, double disparity, Eigen::Vector3d& out) const {
  if (!std::isfinite(disparity)) return false;
  const Eigen::Vector4d h = Q * Eigen::Vector4d(x, y, disparity, 1.0);
  if (!(h[3] > 0)) return false;
  out = h.head<3>() / h[3];
  return true;
}

Eigen::Matrix4d StereoCamera::plane_map() const { return Q.inverse().transpose(); }

bool StereoCamera::plane_normal(const Eigen::Matrix4d& plane_map, double a, double b, double c,
                                const Eigen::Vector3d& point_on_plane, Eigen::Vector3d& out) {
  // Q maps (x, y, d, 1) to homogeneous 3D points, so the plane (a, b, -1, c) . u = 0
  // maps to Q^-T (a, b, -1, c) . P = 0.
  const Eigen::Vector4d plane = plane_map * Eigen::Vector4d(a, b, -1.0, c);
  Eigen::Vector3d normal = plane.head<3>();
  const double norm = normal.norm();
  if (!(norm > 0) || !std::isfinite(norm)) return false;
  normal /= norm;
  // Face the camera at the origin: the normal points against the viewing ray.
  if (normal.dot(point_on_plane) > 0) normal = -normal;
  out = normal;
  return true;
}

StereoCamera StereoCamera::resized_to(int image_width, int image_height) const {
  if (width <= 0 || height <= 0 || (width == image_width && height == image_height)) return *this;
  const double sx = static_cast<double>(image_width) / width;
  const double sy = static_cast<double>(image_height) / height;
  // Rounding when an image was resized can change a side by a pixel.
  if (std::abs(sx * height - image_height) > 1.0 || std::abs(sy * width - image_width) > 1.0) {
    std::ostringstream why;
    why << "is for " << width << "x" << height << " images, not " << image_width << "x"
        << image_height << " (not a uniform resize)";
    throw InputError(source, why.str());
  }
  StereoCamera resized = *this;
  const double s = sx;
  Eigen::Matrix4d scale = Eigen::Matrix4d::Identity();
  scale(0, 0) = scale(1, 1) = scale(2, 2) = 1.0 / s;
  resized.Q = Q * scale;
  resized.width = image_width;
  resized.height = image_height;
  return resized;
}

}  // namespace flexsight

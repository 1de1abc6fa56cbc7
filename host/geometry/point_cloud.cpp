#include "host/geometry/point_cloud.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core/utility.hpp>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

void check_same_size(const cv::Mat& disparity, const cv::Mat& other, int type, const char* what) {
  if (other.empty()) return;
  if (other.size() != disparity.size() || other.type() != type) {
    throw InputError(what, "is " + std::to_string(other.cols) + "x" + std::to_string(other.rows) +
                               " with " + std::to_string(other.channels()) +
                               " channel(s), the disparity " + std::to_string(disparity.cols) +
                               "x" + std::to_string(disparity.rows));
  }
}

bool has_disparity(float d) { return std::isfinite(d) && d >= 0.0f; }

// Slope of the disparity at (x, y) from its valid neighbours, as a plane through the
// pixel: used when only a disparity map is at hand.
cv::Vec3f plane_from_slope(const cv::Mat& disparity, int x, int y) {
  const float d = disparity.at<float>(y, x);
  auto slope = [&](int dx, int dy) {
    const int x0 = x - dx, y0 = y - dy, x1 = x + dx, y1 = y + dy;
    const bool back = x0 >= 0 && y0 >= 0 && has_disparity(disparity.at<float>(y0, x0));
    const bool ahead = x1 < disparity.cols && y1 < disparity.rows &&
                       has_disparity(disparity.at<float>(y1, x1));
    if (back && ahead) return (disparity.at<float>(y1, x1) - disparity.at<float>(y0, x0)) / 2.0f;
    if (ahead) return disparity.at<float>(y1, x1) - d;
    if (back) return d - disparity.at<float>(y0, x0);
    return 0.0f;
  };
  const float a = slope(1, 0);
  const float b = slope(0, 1);
  return {a, b, d - a * static_cast<float>(x) - b * static_cast<float>(y)};
}

// Least-squares plane d = a x + b y + c through the neighbours of (x, y) that lie within
// `inlier` of `guide` (the pixel's plane). Coordinates are relative to (x, y) so the
// 3x3 normal equations stay well conditioned. Returns `guide` when the fit is degenerate.
cv::Vec3f fitted_plane(const cv::Mat& disparity, int x, int y, const cv::Vec3f& guide,
                       const NormalOptions& options) {
  const int r = options.fit_radius;
  Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  int used = 0;
  // Every second row and column: a quarter of the work for the same plane (the
  // disparities of neighbouring pixels are strongly correlated anyway).
  for (int v = y - r; v <= y + r; v += 2) {
    if (v < 0 || v >= disparity.rows) continue;
    const float* row = disparity.ptr<float>(v);
    for (int u = x - r; u <= x + r; u += 2) {
      if (u < 0 || u >= disparity.cols) continue;
      const float d = row[u];
      if (!has_disparity(d)) continue;
      const float predicted = guide[0] * u + guide[1] * v + guide[2];
      if (!(std::abs(d - predicted) <= options.inlier_disparity)) continue;
      const Eigen::Vector3d s(u - x, v - y, 1.0);
      normal_matrix += s * s.transpose();
      rhs += s * static_cast<double>(d);
      ++used;
    }
  }
  if (used < 6) return guide;
  const Eigen::Vector3d abc = normal_matrix.ldlt().solve(rhs);
  if (!abc.allFinite()) return guide;
  // Back to absolute pixel coordinates: d = a (u - x) + b (v - y) + c0.
  return {static_cast<float>(abc[0]), static_cast<float>(abc[1]),
          static_cast<float>(abc[2] - abc[0] * x - abc[1] * y)};
}

}  // namespace

PointCloud build_point_cloud(const cv::Mat& disparity, const cv::Mat& left_rgb,
                             const cv::Mat& planes, const cv::Mat& confidence,
                             const StereoCamera& camera, const CloudFilter& filter,
                             const NormalOptions& normals) {
  if (disparity.empty() || disparity.type() != CV_32FC1) {
    throw InputError("disparity", "must be a non-empty one-channel float map");
  }
  check_same_size(disparity, left_rgb, CV_8UC3, "left image");
  check_same_size(disparity, planes, CV_32FC3, "planes");
  check_same_size(disparity, confidence, CV_32FC1, "confidence map");
  if (left_rgb.empty()) throw InputError("left image", "is required for the point colours");
  if (filter.min_confidence > 0 && confidence.empty()) {
    throw InputError("confidence filter", "needs a confidence map");
  }
  // Points and normals per pixel in parallel (rows are independent), then kept pixels
  // are gathered in row-major order, so the cloud does not depend on the thread count.
  const Eigen::Matrix4d plane_map = camera.plane_map();
  const int width = disparity.cols;
  std::vector<Eigen::Vector3f> points(disparity.total()), point_normals(disparity.total());
  std::vector<std::uint8_t> keep(disparity.total(), 0);
  cv::parallel_for_(cv::Range(0, disparity.rows), [&](const cv::Range& rows) {
    for (int y = rows.start; y < rows.end; ++y) {
      for (int x = 0; x < width; ++x) {
        const float d = disparity.at<float>(y, x);
        if (!has_disparity(d)) continue;
        const float conf = confidence.empty() ? 1.0f : confidence.at<float>(y, x);
        if (!(conf >= filter.min_confidence)) continue;
        Eigen::Vector3d point;
        if (!camera.point(x, y, d, point)) continue;
        if (filter.min_depth > 0 && point.z() < filter.min_depth) continue;
        if (filter.max_depth > 0 && point.z() > filter.max_depth) continue;
        cv::Vec3f plane =
            planes.empty() ? plane_from_slope(disparity, x, y) : planes.at<cv::Vec3f>(y, x);
        if (normals.fit_radius > 0) plane = fitted_plane(disparity, x, y, plane, normals);
        Eigen::Vector3d normal;
        if (!StereoCamera::plane_normal(plane_map, plane[0], plane[1], plane[2], point, normal)) {
          normal = -point.normalized();  // degenerate plane: face the camera
        }
        const size_t i = static_cast<size_t>(y) * width + x;
        points[i] = point.cast<float>();
        point_normals[i] = normal.cast<float>();
        keep[i] = 1;
      }
    }
  });
  PointCloud cloud;
  cloud.unit = camera.unit;
  const size_t kept = static_cast<size_t>(std::count(keep.begin(), keep.end(), 1));
  cloud.points.reserve(kept);
  cloud.normals.reserve(kept);
  cloud.colors.reserve(kept);
  cloud.pixel.reserve(kept);
  for (size_t i = 0; i < keep.size(); ++i) {
    if (!keep[i]) continue;
    cloud.points.push_back(points[i]);
    cloud.normals.push_back(point_normals[i]);
    const int y = static_cast<int>(i) / width, x = static_cast<int>(i) % width;
    cloud.colors.push_back(left_rgb.at<cv::Vec3b>(y, x));
    if (!confidence.empty()) cloud.confidence.push_back(confidence.at<float>(y, x));
    cloud.pixel.push_back(static_cast<int>(i));
  }
  return cloud;
}

}  // namespace flexsight

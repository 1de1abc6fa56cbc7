#include "host/segment/floor_plane.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Height histogram bins (mm) when looking for the floor's level.
constexpr double kLevelBinMm = 1.0;

std::vector<Eigen::Vector3d> sample_points(const cv::Mat& depth_mm, const PinholeCamera& camera, int step) {
  std::vector<Eigen::Vector3d> points;
  for (int v = step / 2; v < depth_mm.rows; v += step) {
    const float* row = depth_mm.ptr<float>(v);
    for (int u = step / 2; u < depth_mm.cols; u += step) {
      if (row[u] > 0.0f && std::isfinite(row[u])) points.push_back(back_project(camera, u, v, row[u]));
    }
  }
  return points;
}

// The least-squares plane through `points` (their centroid, the covariance's smallest
// axis), its normal turned to the camera.
FloorPlane plane_through(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) covariance += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  FloorPlane plane;
  plane.normal = solver.eigenvectors().col(0);
  if (plane.normal.dot(centroid) > 0.0) plane.normal = -plane.normal;
  plane.offset = -plane.normal.dot(centroid);
  plane.found = true;
  return plane;
}

// The widest plane facing the camera by RANSAC (fixed seed), refitted to its inliers.
FloorPlane widest_plane(const std::vector<Eigen::Vector3d>& points, double tolerance, const FloorPlaneOptions& options) {
  cv::RNG rng(0x5eedf100);
  const double min_facing = std::cos(options.max_tilt_deg * kPi / 180.0);
  const int n = static_cast<int>(points.size());
  FloorPlane best;
  long best_count = 0;
  for (int it = 0; it < options.iterations; ++it) {
    const Eigen::Vector3d& a = points[rng.uniform(0, n)];
    const Eigen::Vector3d& b = points[rng.uniform(0, n)];
    const Eigen::Vector3d& c = points[rng.uniform(0, n)];
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.norm() < 1e-9) continue;
    normal.normalize();
    if (normal.dot(a) > 0.0) normal = -normal;
    if (-normal.z() < min_facing) continue;  // a wall or a part's side, not a floor
    const double offset = -normal.dot(a);
    long count = 0;
    for (const Eigen::Vector3d& p : points) count += std::abs(normal.dot(p) + offset) < tolerance;
    if (count > best_count) {
      best_count = count;
      best.normal = normal;
      best.offset = offset;
      best.found = true;
    }
  }
  if (!best.found) return best;
  std::vector<Eigen::Vector3d> inliers;
  for (const Eigen::Vector3d& p : points) {
    if (std::abs(best.height(p)) < tolerance) inliers.push_back(p);
  }
  return inliers.size() >= 3 ? plane_through(inliers) : best;
}

}  // namespace

void FloorPlaneOptions::check() const {
  if (sample_step < 0) throw InputError("floor plane", "sample step must not be negative");
  if (iterations < 1) throw InputError("floor plane", "needs at least one RANSAC iteration");
  if (!(inlier_ratio > 0.0 && inlier_ratio < 1.0)) throw InputError("floor plane", "inlier ratio must lie in (0, 1)");
  if (!(max_tilt_deg > 0.0 && max_tilt_deg <= 90.0)) throw InputError("floor plane", "max tilt must lie in (0, 90]");
  if (!(max_rise_mm >= 0.0)) throw InputError("floor plane", "max rise must not be negative");
  if (!(min_share > 0.0 && min_share <= 1.0)) throw InputError("floor plane", "min share must lie in (0, 1]");
}

FloorPlane fit_floor_plane(const cv::Mat& depth_mm, const PinholeCamera& camera, const FloorPlaneOptions& options) {
  options.check();
  CV_Assert(depth_mm.type() == CV_32FC1);
  const int step = options.sample_step > 0 ? options.sample_step
                                           : std::max(1, std::min(depth_mm.cols / 300, depth_mm.rows / 240));
  const std::vector<Eigen::Vector3d> points = sample_points(depth_mm, camera, step);
  if (points.size() < 30) return {};
  std::vector<double> depths;
  for (const Eigen::Vector3d& p : points) depths.push_back(p.z());
  std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
  const double tolerance = options.inlier_ratio * depths[depths.size() / 2];
  FloorPlane widest = widest_plane(points, tolerance, options);
  if (!widest.found) return widest;

  // The highest level parallel to the widest plane, within max_rise_mm of it, holding
  // min_share of the points within the tolerance.
  const int bins = static_cast<int>(std::ceil((options.max_rise_mm + 2.0 * tolerance) / kLevelBinMm)) + 1;
  std::vector<long> histogram(bins, 0);
  for (const Eigen::Vector3d& p : points) {
    const double h = widest.height(p) + tolerance;
    if (h >= 0.0 && h < bins * kLevelBinMm) ++histogram[static_cast<int>(h / kLevelBinMm)];
  }
  const int window = std::max(1, static_cast<int>(std::lround(2.0 * tolerance / kLevelBinMm)));
  const long needed = static_cast<long>(std::ceil(options.min_share * points.size()));
  int chosen = -1;
  for (int start = bins - window; start >= 0 && chosen < 0; --start) {
    long count = 0;
    for (int b = start; b < start + window; ++b) count += histogram[b];
    if (count >= needed) chosen = start;
  }
  // The fullest window just below the first that qualified (its upper edge may only
  // graze the level), then the mean height of its points.
  long best_count = -1;
  const int first = chosen;
  for (int start = std::max(0, first - window); first >= 0 && start <= first; ++start) {
    long count = 0;
    for (int b = start; b < start + window; ++b) count += histogram[b];
    if (count > best_count) best_count = count, chosen = start;
  }
  double rise = 0.0;
  if (chosen >= 0) {
    const double low = chosen * kLevelBinMm - tolerance, high = low + window * kLevelBinMm;
    double sum = 0.0;
    long count = 0;
    for (const Eigen::Vector3d& p : points) {
      const double h = widest.height(p);
      if (h >= low && h < high) sum += h, ++count;
    }
    if (count > 0) rise = sum / count;
  }
  FloorPlane floor = widest;
  floor.offset -= std::max(0.0, rise);
  long on_floor = 0;
  for (const Eigen::Vector3d& p : points) on_floor += std::abs(floor.height(p)) < tolerance;
  floor.inlier_share = static_cast<double>(on_floor) / points.size();
  return floor;
}

}  // namespace flexsight

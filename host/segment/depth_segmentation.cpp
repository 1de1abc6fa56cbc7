#include "host/segment/depth_segmentation.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Union-find over pixel indices, with path halving.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// CV_8UC1: 255 where the measured surface is higher than the floor by more than the margin.
cv::Mat above_floor(const cv::Mat& depth_mm, const PinholeCamera& camera, const FloorPlane& floor, double margin) {
  cv::Mat mask(depth_mm.size(), CV_8UC1, cv::Scalar(0));
  if (!floor.found) return mask;
  for (int v = 0; v < depth_mm.rows; ++v) {
    const float* z = depth_mm.ptr<float>(v);
    unsigned char* m = mask.ptr<unsigned char>(v);
    for (int u = 0; u < depth_mm.cols; ++u) {
      if (z[u] > 0.0f && std::isfinite(z[u]) && floor.height(back_project(camera, u, v, z[u])) > margin) m[u] = 255;
    }
  }
  return mask;
}

// Labels 1..count of the mask's pixels joined to 4-neighbours whose depth differs by less
// than step_ratio of theirs; 0 elsewhere.
cv::Mat connected_regions(const cv::Mat& depth_mm, const cv::Mat& mask, double step_ratio, int* count) {
  const int w = depth_mm.cols, h = depth_mm.rows;
  DisjointSets sets(w * h);
  auto close = [&](float a, float b) { return std::abs(a - b) < step_ratio * std::min(a, b); };
  for (int v = 0; v < h; ++v) {
    const float* z = depth_mm.ptr<float>(v);
    const unsigned char* m = mask.ptr<unsigned char>(v);
    for (int u = 0; u < w; ++u) {
      if (!m[u]) continue;
      if (u + 1 < w && m[u + 1] && close(z[u], z[u + 1])) sets.join(v * w + u, v * w + u + 1);
      if (v + 1 < h && mask.at<unsigned char>(v + 1, u) && close(z[u], depth_mm.at<float>(v + 1, u))) {
        sets.join(v * w + u, (v + 1) * w + u);
      }
    }
  }
  cv::Mat labels(depth_mm.size(), CV_32SC1, cv::Scalar(0));
  std::vector<int> label_of_root(w * h, 0);
  *count = 0;
  for (int i = 0; i < w * h; ++i) {
    if (!mask.data[i]) continue;
    int& label = label_of_root[sets.find(i)];
    if (label == 0) label = ++*count;
    labels.at<int>(i / w, i % w) = label;
  }
  return labels;
}

// A flat region tilted away from the floor: a bin wall seen from inside.
bool is_wall(const std::vector<Eigen::Vector3d>& points, const FloorPlane& floor, double extent,
             const DepthSegmentationOptions& options) {
  if (points.size() < 3) return false;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) covariance += (p - centroid) * (p - centroid).transpose();
  covariance /= static_cast<double>(points.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const double thickness = std::sqrt(std::max(0.0, solver.eigenvalues()(0)));
  const double tilt = std::acos(std::min(1.0, std::abs(solver.eigenvectors().col(0).dot(floor.normal)))) * 180.0 / kPi;
  return thickness < options.wall_flatness * extent && tilt > options.wall_tilt_deg;
}

struct RegionPixels {
  cv::Rect box;
  std::vector<float> depths;
  std::vector<Eigen::Vector3d> points;  // every 2nd pixel on both axes, for the wall test
};

std::vector<RegionPixels> gather(const cv::Mat& labels, const cv::Mat& depth_mm, const PinholeCamera& camera, int count) {
  std::vector<RegionPixels> regions(count + 1);
  std::vector<cv::Point> low(count + 1, cv::Point(labels.cols, labels.rows)), high(count + 1, cv::Point(-1, -1));
  for (int v = 0; v < labels.rows; ++v) {
    const int* l = labels.ptr<int>(v);
    const float* z = depth_mm.ptr<float>(v);
    for (int u = 0; u < labels.cols; ++u) {
      if (!l[u]) continue;
      RegionPixels& r = regions[l[u]];
      r.depths.push_back(z[u]);
      if ((u | v) % 2 == 0) r.points.push_back(back_project(camera, u, v, z[u]));
      low[l[u]] = {std::min(low[l[u]].x, u), std::min(low[l[u]].y, v)};
      high[l[u]] = {std::max(high[l[u]].x, u), std::max(high[l[u]].y, v)};
    }
  }
  for (int i = 1; i <= count; ++i) regions[i].box = cv::Rect(low[i], high[i] + cv::Point(1, 1));
  return regions;
}

// Drops the regions whose box lies mostly inside the box of a larger one.
void drop_nested(std::vector<DepthRegion>& regions, double share) {
  std::vector<DepthRegion> kept;
  for (const DepthRegion& r : regions) {
    const bool nested = std::any_of(regions.begin(), regions.end(), [&](const DepthRegion& other) {
      return other.pixels > r.pixels && (other.box & r.box).area() >= share * r.box.area();
    });
    if (!nested) kept.push_back(r);
  }
  regions = std::move(kept);
}

}  // namespace

void DepthSegmentationOptions::check() const {
  floor.check();
  if (!(margin_mm >= 0.0)) throw InputError("depth segmentation", "margin must not be negative");
  if (!(step_ratio > 0.0)) throw InputError("depth segmentation", "depth step ratio must be positive");
  if (!(smallest_part_mm > 0.0 && largest_part_mm >= smallest_part_mm)) {
    throw InputError("depth segmentation", "needs the parts' smallest and largest diameters");
  }
  if (!(min_extent > 0.0 && max_extent >= min_extent)) throw InputError("depth segmentation", "bad extent bounds");
  if (!(min_area >= 0.0)) throw InputError("depth segmentation", "min area must not be negative");
  if (!(nested_share > 0.0 && nested_share <= 1.0)) throw InputError("depth segmentation", "nested share must lie in (0, 1]");
}

DepthSegmentation segment_depth(const cv::Mat& depth_mm, const PinholeCamera& camera,
                                const DepthSegmentationOptions& options) {
  options.check();
  CV_Assert(depth_mm.type() == CV_32FC1);
  DepthSegmentation result;
  result.floor = fit_floor_plane(depth_mm, camera, options.floor);
  const cv::Mat mask = above_floor(depth_mm, camera, result.floor, options.margin_mm);
  result.labels = connected_regions(depth_mm, mask, options.step_ratio, &result.region_count);
  std::vector<RegionPixels> regions = gather(result.labels, depth_mm, camera, result.region_count);
  const cv::Rect image(cv::Point(), depth_mm.size());
  for (int label = 1; label <= result.region_count; ++label) {
    RegionPixels& r = regions[label];
    // A region cut by the image's edge is no whole part (and often the bin's rim).
    if (r.box.x == 0 || r.box.y == 0 || r.box.br().x == image.width || r.box.br().y == image.height) continue;
    std::nth_element(r.depths.begin(), r.depths.begin() + r.depths.size() / 2, r.depths.end());
    DepthRegion region;
    region.label = label;
    region.box = r.box;
    region.pixels = static_cast<int>(r.depths.size());
    region.depth_mm = r.depths[r.depths.size() / 2];
    region.extent_mm = std::hypot(r.box.width, r.box.height) * region.depth_mm / camera.fx;
    region.score = static_cast<double>(region.pixels) / r.box.area();
    const double pixel_mm = region.depth_mm / camera.fx;
    region.area_mm2 = region.pixels * pixel_mm * pixel_mm;
    const double min_side = options.min_area * options.smallest_part_mm;
    if (region.area_mm2 < min_side * min_side) continue;
    if (region.extent_mm < options.min_extent * options.smallest_part_mm) continue;
    if (region.extent_mm > options.max_extent * options.largest_part_mm) continue;
    if (is_wall(r.points, result.floor, region.extent_mm, options)) continue;
    result.regions.push_back(region);
  }
  drop_nested(result.regions, options.nested_share);
  return result;
}

}  // namespace flexsight

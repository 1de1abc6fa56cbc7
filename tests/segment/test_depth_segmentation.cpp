// The depth segmentation (host/segment) on depth maps made here by casting rays at a few
// shapes: a floor, blocks and a lying cylinder on it, a bin floor above a table, a wall.
// Each part is found as one region whose box is the part's, parts touching at
// different heights are split, and the floor is the bin's, not the table's.
#include "host/segment/depth_segmentation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <opencv2/imgproc.hpp>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

constexpr double kFloorZ = 1000.0;

PinholeCamera test_camera() { return centred_camera(640, 480, 600.0); }

// Depth (mm) where each pixel's ray first meets `surface`: a function giving, for a ray
// direction (z = 1), the distance t along it (the depth), or a huge value for a miss.
cv::Mat cast(const PinholeCamera& camera, const std::function<double(const Eigen::Vector3d&)>& surface) {
  cv::Mat depth(camera.height, camera.width, CV_32FC1, cv::Scalar(0));
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0);
      const double t = surface(ray);
      if (t < 1e8) depth.at<float>(v, u) = static_cast<float>(t);
    }
  }
  return depth;
}

// A block's top face: the rectangle [x0, x1] x [y0, y1] (mm, camera frame) at depth z.
double block_top(const Eigen::Vector3d& ray, double x0, double x1, double y0, double y1, double z) {
  const double x = ray.x() * z, y = ray.y() * z;
  return x >= x0 && x <= x1 && y >= y0 && y <= y1 ? z : 1e9;
}

// A cylinder lying along x on the floor at depth floor_z: radius r, axis at y = yc.
double lying_cylinder(const Eigen::Vector3d& ray, double x0, double x1, double yc, double r, double floor_z) {
  const double zc = floor_z - r;
  // |(t ry - yc, t - zc)| = r
  const double a = ray.y() * ray.y() + 1.0, b = -2.0 * (ray.y() * yc + zc), c = yc * yc + zc * zc - r * r;
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return 1e9;
  const double t = (-b - std::sqrt(disc)) / (2.0 * a);
  const double x = ray.x() * t;
  return x >= x0 && x <= x1 ? t : 1e9;
}

DepthSegmentationOptions part_sizes(double smallest, double largest) {
  DepthSegmentationOptions options;
  options.smallest_part_mm = smallest;
  options.largest_part_mm = largest;
  return options;
}

// The box of the pixels whose depth lies in (z_min, z_max) inside `area`.
cv::Rect pixels_between(const cv::Mat& depth, float z_min, float z_max, cv::Rect area) {
  std::vector<cv::Point> points;
  for (int v = area.y; v < area.br().y; ++v) {
    for (int u = area.x; u < area.br().x; ++u) {
      const float z = depth.at<float>(v, u);
      if (z > z_min && z < z_max) points.push_back({u, v});
    }
  }
  return cv::boundingRect(points);
}

double iou(const cv::Rect& a, const cv::Rect& b) {
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter);
}

TEST(DepthSegmentation, FindsEachPartOnAFloorAndSplitsTouchingPartsAtADepthStep) {
  const PinholeCamera camera = test_camera();
  const cv::Mat depth = cast(camera, [](const Eigen::Vector3d& ray) {
    double t = kFloorZ;
    t = std::min(t, block_top(ray, -250, -170, -150, -90, kFloorZ - 30));  // a block, 30 mm high
    t = std::min(t, lying_cylinder(ray, 80, 200, -120, 20, kFloorZ));     // a lying cylinder
    // Two blocks side by side, touching, 25 and 60 mm high.
    t = std::min(t, block_top(ray, -100, -30, 60, 130, kFloorZ - 25));
    t = std::min(t, block_top(ray, -30, 40, 60, 130, kFloorZ - 60));
    return t;
  });
  const DepthSegmentation segmentation = segment_depth(depth, camera, part_sizes(60.0, 160.0));
  ASSERT_TRUE(segmentation.floor.found);
  EXPECT_NEAR(segmentation.floor.normal.z(), -1.0, 1e-6);
  EXPECT_NEAR(segmentation.floor.offset, kFloorZ, 0.5);
  ASSERT_EQ(segmentation.regions.size(), 4u);

  // Each part's pixels (by their depth, in the part of the image it lies in), against the
  // region whose box overlaps it most.
  const std::vector<cv::Rect> truth = {
      pixels_between(depth, 0, kFloorZ - 10, {0, 0, 320, 240}),               // block
      pixels_between(depth, 0, kFloorZ - 10, {320, 0, 320, 240}),             // cylinder
      pixels_between(depth, 0, kFloorZ - 40, {0, 240, 640, 240}),             // the high block
      pixels_between(depth, kFloorZ - 40, kFloorZ - 10, {0, 240, 640, 240}),  // the low block
  };
  for (const cv::Rect& part : truth) {
    double best = 0.0;
    for (const DepthRegion& region : segmentation.regions) best = std::max(best, iou(region.box, part));
    EXPECT_GT(best, 0.8) << "part at " << part;
  }
  for (const DepthRegion& region : segmentation.regions) {
    EXPECT_GT(region.score, 0.5);
    EXPECT_LE(region.score, 1.0);
  }
}

TEST(DepthSegmentation, TakesTheBinFloorAboveTheTableAndDropsTheWallAndSmallSpecks) {
  const PinholeCamera camera = test_camera();
  // A table at 1010 mm, the widest plane in view; on it a bin whose floor is 10 mm thick
  // spans x in [-150, 250]; a wall 150 mm high on its right, seen from inside as a slope
  // (x from 250 to 270 as it rises), short enough to pass as a part by its size; one
  // block in the bin and a 10-mm speck.
  const cv::Mat depth = cast(camera, [](const Eigen::Vector3d& ray) {
    const double x = ray.x() * kFloorZ;
    double t = kFloorZ + 10.0;
    if (x >= -150 && x <= 250) t = kFloorZ;
    t = std::min(t, block_top(ray, -100, 0, -40, 40, kFloorZ - 40));
    t = std::min(t, block_top(ray, 100, 110, 0, 10, kFloorZ - 20));
    // The wall: the plane x = 250 + (1000 - z) 20 / 150, between z 850 and 1000.
    const double wall = (250.0 + kFloorZ * 20.0 / 150.0) / (ray.x() + 20.0 / 150.0);
    if (wall >= kFloorZ - 150.0 && wall <= kFloorZ && std::abs(ray.y() * wall) < 50.0) t = std::min(t, wall);
    return t;
  });
  const DepthSegmentation segmentation = segment_depth(depth, camera, part_sizes(60.0, 160.0));
  ASSERT_TRUE(segmentation.floor.found);
  EXPECT_NEAR(segmentation.floor.offset, kFloorZ, 1.0);  // the bin floor, not the table
  EXPECT_GE(segmentation.region_count, 3);               // block, speck, wall
  ASSERT_EQ(segmentation.regions.size(), 1u);
  EXPECT_GT(iou(segmentation.regions[0].box, pixels_between(depth, 0, kFloorZ - 30, {0, 0, 420, 480})), 0.9);
}

TEST(DepthSegmentation, FitsATiltedFloor) {
  const PinholeCamera camera = test_camera();
  // The floor turned 15 degrees about the x axis: z = 1000 + y tan(15).
  const double slope = std::tan(15.0 * 3.14159265358979323846 / 180.0);
  const cv::Mat depth = cast(camera, [&](const Eigen::Vector3d& ray) { return kFloorZ / (1.0 - ray.y() * slope); });
  const FloorPlane floor = fit_floor_plane(depth, camera);
  ASSERT_TRUE(floor.found);
  const Eigen::Vector3d expected = Eigen::Vector3d(0.0, slope, -1.0).normalized();
  EXPECT_GT(floor.normal.dot(expected), std::cos(0.2 * 3.14159265358979323846 / 180.0));
  EXPECT_GT(floor.inlier_share, 0.99);
}

TEST(DepthSegmentation, NothingMeasuredGivesNoFloorAndNoRegion) {
  const PinholeCamera camera = test_camera();
  const DepthSegmentation segmentation =
      segment_depth(cv::Mat::zeros(camera.height, camera.width, CV_32FC1), camera, part_sizes(60.0, 160.0));
  EXPECT_FALSE(segmentation.floor.found);
  EXPECT_TRUE(segmentation.regions.empty());
}

TEST(DepthSegmentation, RefusesOptionsWithoutPartSizes) {
  const PinholeCamera camera = test_camera();
  const cv::Mat depth(camera.height, camera.width, CV_32FC1, cv::Scalar(kFloorZ));
  EXPECT_THROW(segment_depth(depth, camera, DepthSegmentationOptions()), InputError);
  EXPECT_THROW(segment_depth(depth, camera, part_sizes(100.0, 50.0)), InputError);
}

}  // namespace
}  // namespace flexsight

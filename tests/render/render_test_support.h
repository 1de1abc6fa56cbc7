#pragma once
// Shapes, poses and paths the renderer's tests share: fixture meshes, the T-LESS parts,
// analytic test shapes (a square of two triangles, a box) and poses from axis-angles.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstring>
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "host/render/mesh.h"
#include "host/render/raycaster.h"

namespace flexsight::testing_support {

inline std::string render_fixture(const std::string& name) {
  return std::string(FLEXSIGHT_TEST_DATA_DIR) + "/render/" + name;
}

// The 23 T-LESS CAD models (FLEXSIGHT_TLESS_CAD_DIR, set by CMake; see
// ../shared/detection/README.md). A missing file fails the test that reads it.
inline std::filesystem::path tless_cad_path(const std::string& object) {
  return std::filesystem::path(FLEXSIGHT_TLESS_CAD_DIR) / ("obj_" + object + ".stl");
}

inline ::testing::AssertionResult file_present(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_regular_file(path, error)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << path << " does not exist (FLEXSIGHT_TLESS_CAD_DIR, ../shared/detection/cad/tless "
         << "beside the checkout by default)";
}

// A square of side 2 * half in the z = 0 plane of its frame, as two triangles sharing
// the diagonal.
inline std::shared_ptr<const Mesh> square_mesh(float half) {
  return std::make_shared<const Mesh>(
      make_mesh("square", {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}},
                {{0, 1, 2}, {0, 2, 3}}));
}

// The box [-h, h] (per axis) as 12 triangles, counter-clockwise from outside.
inline std::shared_ptr<const Mesh> box_mesh(const Eigen::Vector3f& h) {
  std::vector<Eigen::Vector3f> v;
  for (int i = 0; i < 8; ++i) {
    v.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  }
  // Quads by corner bits, wound so that their normals point out of the box.
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {1, 3, 7, 5}, {0, 4, 6, 2}};
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (const auto& q : quads) {
    triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])});
    triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])});
  }
  return std::make_shared<const Mesh>(make_mesh("box", v, triangles));
}

inline Pose make_pose(double degrees, const Eigen::Vector3d& axis, const Eigen::Vector3d& t) {
  Pose pose;
  pose.R = Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
  pose.t = t;
  return pose;
}

// The camera ray of pixel (u, v) in double precision, z = 1.
inline Eigen::Vector3d pixel_ray(const PinholeCamera& camera, int u, int v) {
  return {(u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0};
}

inline bool same_mat_bytes(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return false;
  const cv::Mat ca = a.clone(), cb = b.clone();
  return std::memcmp(ca.data, cb.data, ca.total() * ca.elemSize()) == 0;
}

}  // namespace flexsight::testing_support

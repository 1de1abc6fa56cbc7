// Google Benchmark of point-to-plane ICP: one refine() of T-LESS obj_05, 650 mm in front
// of a 640x480 camera, from a pose 10 degrees and 10 mm off, with 2000 scene points
// (noise 0.5 mm along the rays, a fifth of them outliers) against 3000 points of the
// part's visible surface; and building the model's k-d tree. Counters: iterations.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "host/pose/point_to_plane_icp.h"
#include "host/pose/pose_math.h"
#include "host/render/mesh.h"
#include "host/render/raycaster.h"

namespace flexsight {
namespace {

struct IcpCase {
  std::vector<Eigen::Vector3f> model_points, model_normals, scene;
  Pose initial;
  bool ok = true;
  std::string error;

  IcpCase() {
    try {
      const auto path = std::filesystem::path(FLEXSIGHT_TLESS_CAD_DIR) / "obj_05.stl";
      RenderScene render;
      Pose truth;
      truth.R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 0.4, -0.3).normalized())
                    .toRotationMatrix();
      truth.t = {15.0, -10.0, 650.0};
      render.add_instance(
          render.add_mesh(std::make_shared<const Mesh>(load_mesh(path.string()))), truth);
      render.commit();
      const PinholeCamera camera;
      const RaycastImages images = raycast(render, camera);
      std::mt19937 rng(3);
      std::normal_distribution<double> noise(0.0, 0.5);
      std::vector<Eigen::Vector3f> part;
      for (int v = 0; v < camera.height; ++v) {
        for (int u = 0; u < camera.width; ++u) {
          if (images.instance.at<std::int32_t>(v, u) != 0) continue;
          const cv::Vec3f& p = images.point.at<cv::Vec3f>(v, u);
          const cv::Vec3f& n = images.geometric_normal.at<cv::Vec3f>(v, u);
          const Eigen::Vector3d point(p[0], p[1], p[2]);
          model_points.push_back((truth.R.transpose() * (point - truth.t)).cast<float>());
          model_normals.push_back(
              (truth.R.transpose() * Eigen::Vector3d(n[0], n[1], n[2])).cast<float>());
          part.push_back((point + noise(rng) * point.normalized()).cast<float>());
        }
      }
      // 3000 of the ~4700 model points (a render at a lower resolution would give as
      // many), 1600 part points and 400 outliers scattered in the part's box grown by
      // 20 mm.
      std::vector<size_t> order(model_points.size());
      for (size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::shuffle(order.begin(), order.end(), rng);
      order.resize(std::min<size_t>(order.size(), 3000));
      std::vector<Eigen::Vector3f> points, normals;
      for (size_t i : order) {
        points.push_back(model_points[i]);
        normals.push_back(model_normals[i]);
      }
      model_points = std::move(points);
      model_normals = std::move(normals);
      std::shuffle(part.begin(), part.end(), rng);
      part.resize(std::min<size_t>(part.size(), 1600));
      Eigen::AlignedBox3f box;
      for (const auto& p : part) box.extend(p);
      std::uniform_real_distribution<float> unit(0.0f, 1.0f);
      scene = part;
      for (int i = 0; i < 400; ++i) {
        const Eigen::Vector3f t(unit(rng), unit(rng), unit(rng));
        scene.push_back(box.min().array() - 20.0f +
                        t.array() * (box.sizes().array() + 40.0f));
      }
      std::normal_distribution<double> gauss(0.0, 1.0);
      const Eigen::Vector3d axis =
          Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
      const Eigen::Vector3d direction =
          Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
      initial.R = rotation_from_axis_angle(10.0 * M_PI / 180.0 * axis) * truth.R;
      initial.t = truth.t + 10.0 * direction;
    } catch (const std::exception& e) {
      ok = false;
      error = e.what();
    }
  }
};

const IcpCase& icp_case() {
  static const IcpCase c;
  return c;
}

void BM_Icp_Refine(benchmark::State& state) {
  const IcpCase& c = icp_case();
  if (!c.ok) {
    state.SkipWithError(c.error.c_str());
    return;
  }
  const PointToPlaneIcp icp(c.model_points, c.model_normals);
  IcpResult result;
  for (auto _ : state) {
    result = icp.refine(c.scene, c.initial, IcpParams());
    benchmark::DoNotOptimize(result.pose.t.data());
  }
  state.counters["iterations"] = result.iterations;
  state.counters["scene_points"] = double(c.scene.size());
  state.counters["model_points"] = double(c.model_points.size());
  state.counters["converged"] = result.converged;
}

void BM_Icp_BuildModel(benchmark::State& state) {
  const IcpCase& c = icp_case();
  if (!c.ok) {
    state.SkipWithError(c.error.c_str());
    return;
  }
  for (auto _ : state) {
    const PointToPlaneIcp icp(c.model_points, c.model_normals);
    benchmark::DoNotOptimize(&icp);
  }
}

BENCHMARK(BM_Icp_Refine)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);
BENCHMARK(BM_Icp_BuildModel)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

}  // namespace
}  // namespace flexsight

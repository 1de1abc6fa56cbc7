// Google Benchmark of the 3D output: disparity and planes to a colored point cloud with
// normals, and writing it as binary PLY, at quarter-resolution Middlebury size.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "host/stereo/confidence_map.h"
#include "host/geometry/point_cloud.h"
#include "host/geometry/ply.h"
#include "tests/common/random_texture.h"

namespace flexsight {
namespace {

// A slanted disparity plane with a bump, its planes, a textured image: what the matcher
// hands the cloud code, at width x height.
struct CloudInputs {
  cv::Mat disparity, planes, image;
  StereoCamera camera;
  CloudInputs(int width, int height) {
    disparity.create(height, width, CV_32FC1);
    planes.create(height, width, CV_32FC3);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const float a = 0.03f, b = 0.01f;
        const float bump = 8.0f * std::exp(-((x - width / 2.0f) * (x - width / 2.0f) +
                                             (y - height / 2.0f) * (y - height / 2.0f)) /
                                           (0.05f * width * width));
        const float d = 20.0f + a * x + b * y + bump;
        disparity.at<float>(y, x) = d;
        planes.at<cv::Vec3f>(y, x) = {a, b, d - a * x - b * y};
      }
    }
    image = testing_support::random_rgb8(width, height, 3);
    camera.Q = reprojection_matrix(1000, width / 2.0, height / 2.0, width / 2.0 + 30, 190);
    camera.width = width;
    camera.height = height;
  }
};

void set_pixel_rate(benchmark::State& state, const cv::Mat& disparity) {
  state.counters["pixels/s"] = benchmark::Counter(
      static_cast<double>(disparity.total()) * state.iterations(), benchmark::Counter::kIsRate);
}

// args: width, height, plane-fit radius (0 = the matcher's planes as they are).
void BM_Cloud_Build(benchmark::State& state) {
  const CloudInputs in(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  NormalOptions normals;
  normals.fit_radius = static_cast<int>(state.range(2));
  for (auto _ : state) {
    PointCloud cloud = build_point_cloud(in.disparity, in.image, in.planes, {}, in.camera, {}, normals);
    benchmark::DoNotOptimize(cloud.points.data());
  }
  set_pixel_rate(state, in.disparity);
}
BENCHMARK(BM_Cloud_Build)
    ->Args({450, 375, 0})
    ->Args({450, 375, 8})
    ->Args({741, 500, 8})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Build and write binary PLY: what `--ply` costs after matching.
void BM_Cloud_BuildAndWritePly(benchmark::State& state) {
  const CloudInputs in(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const std::string path =
      (std::filesystem::temp_directory_path() / "flexsight_bench_cloud.ply").string();
  for (auto _ : state) {
    write_ply(path, build_point_cloud(in.disparity, in.image, in.planes, {}, in.camera));
  }
  std::filesystem::remove(path);
  set_pixel_rate(state, in.disparity);
}
BENCHMARK(BM_Cloud_BuildAndWritePly)->Args({741, 500})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace flexsight

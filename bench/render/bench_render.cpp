// Google Benchmark of the renderer on a bin-like scene of T-LESS parts: the ray caster
// (depth, ids, normals, points) against a minimal raw Embree loop over the same rays
// (rtcIntersect1, and 4x4 packets through rtcIntersect16), the amodal masks, shading
// with hard and soft shadows, and reading a part. Counters: rays/s (primary rays, one
// per pixel) and, for shading, pixels/s.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "host/render/mesh.h"
#include "host/render/primary_rays.h"
#include "host/render/raycaster.h"
#include "host/render/shading.h"
#include "kernels/common/counter_rng.h"

namespace flexsight {
namespace {

std::string tless_path(const std::string& object) {
  return (std::filesystem::path(FLEXSIGHT_TLESS_CAD_DIR) / ("obj_" + object + ".stl")).string();
}

// Twelve parts (six T-LESS objects, twice each) in a 4 x 3 grid about 600 mm from the
// camera, turned by repeatable pseudo-random rotations, over a floor at 700 mm: every
// ray meets a part or the floor, as in a bin seen from above. The camera's focal length
// is its width, so that both sizes see the same scene.
struct BinScene {
  RenderScene scene;
  PinholeCamera camera;
  bool ok = true;
  std::string error;

  BinScene(int width, int height) {
    camera.width = width;
    camera.height = height;
    camera.fx = camera.fy = width;
    camera.cx = (width - 1) / 2.0;
    camera.cy = (height - 1) / 2.0;
    try {
      const char* objects[] = {"02", "05", "11", "19", "26", "30"};
      std::vector<int> meshes;
      for (const char* object : objects) {
        meshes.push_back(
            scene.add_mesh(std::make_shared<const Mesh>(load_mesh(tless_path(object)))));
      }
      for (int i = 0; i < 12; ++i) {
        const fs_u32 h = fs_hash(0xB1A5U + fs_u32(i));
        const Eigen::Vector3d axis(fs_u32_to_unit(h) - 0.5, fs_u32_to_unit(fs_hash(h)) - 0.5,
                                   fs_u32_to_unit(fs_hash(h + 1)) - 0.5);
        Pose pose;
        pose.R = Eigen::AngleAxisd(6.28 * fs_u32_to_unit(fs_hash(h + 2)), axis.normalized())
                     .toRotationMatrix();
        pose.t = {-165.0 + 110.0 * (i % 4), -110.0 + 110.0 * (i / 4), 600.0 + 10.0 * (i % 3)};
        Material material;
        material.albedo = tinted_grey(1, i);
        scene.add_instance(meshes[i % 6], pose, material);
      }
      const float half = 1000.0f;
      const int floor = scene.add_mesh(std::make_shared<const Mesh>(make_mesh(
          "floor", {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}},
          {{0, 1, 2}, {0, 2, 3}})));
      Pose floor_pose;
      floor_pose.t = {0.0, 0.0, 700.0};
      scene.add_instance(floor, floor_pose);
      scene.commit();
    } catch (const std::exception& e) {
      ok = false;
      error = e.what();
    }
  }
};

int threads_of(const benchmark::State& state) {
  return state.range(2) > 0 ? static_cast<int>(state.range(2)) : omp_get_max_threads();
}

void set_rates(benchmark::State& state, const PinholeCamera& camera, const char* name) {
  state.counters[name] = benchmark::Counter(
      double(camera.width) * camera.height * state.iterations(), benchmark::Counter::kIsRate);
  state.SetLabel(std::to_string(camera.width) + "x" + std::to_string(camera.height) + ", " +
                 std::to_string(threads_of(state)) + " thread(s)");
}

// The ray caster's options with the benchmark's thread count.
RaycastOptions raycast_options(const benchmark::State& state) {
  RaycastOptions options;
  options.threads = threads_of(state);
  return options;
}

// raycast(): every output image, OpenMP over 16x16 tiles, 4x4 packets (rtcIntersect16).
void BM_Render_Raycast(benchmark::State& state) {
  BinScene bin(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!bin.ok) return state.SkipWithError(bin.error.c_str());
  const RaycastOptions options = raycast_options(state);
  for (auto _ : state) {
    RaycastImages images = raycast(bin.scene, bin.camera, options);
    benchmark::DoNotOptimize(images.depth.data);
  }
  set_rates(state, bin.camera, "rays/s");
}

// The raw Embree loops' ray directions per column and row, and what they keep of each
// hit: t (the depth) and the instance.
struct RawRays {
  explicit RawRays(const PinholeCamera& camera)
      : dx(camera.width), dy(camera.height), depth(size_t(camera.width) * camera.height),
        instance(depth.size()) {
    for (int u = 0; u < camera.width; ++u) dx[u] = float((u - camera.cx) / camera.fx);
    for (int v = 0; v < camera.height; ++v) dy[v] = float((v - camera.cy) / camera.fy);
  }
  // Keeps the compiler from dropping the casts whose results nobody reads.
  void keep() {
    benchmark::DoNotOptimize(depth.data());
    benchmark::DoNotOptimize(instance.data());
  }
  std::vector<float> dx, dy;
  std::vector<float> depth;
  std::vector<unsigned> instance;
};

// The same rays through rtcIntersect1 alone, keeping only t and the instance: what the
// ray caster would cost without its outputs.
void BM_Render_RawEmbree1(benchmark::State& state) {
  BinScene bin(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!bin.ok) return state.SkipWithError(bin.error.c_str());
  const PinholeCamera& camera = bin.camera;
  RawRays raw(camera);
  const RTCScene top = bin.scene.embree_scene();
  const int threads = threads_of(state);
  for (auto _ : state) {
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
    for (int v = 0; v < camera.height; ++v) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      for (int u = 0; u < camera.width; ++u) {
        RTCRayHit rh;
        set_primary_ray(rh, raw.dx[u], raw.dy[v]);
        rtcIntersect1(top, &context, &rh);
        raw.depth[size_t(v) * camera.width + u] = rh.ray.tfar;
        raw.instance[size_t(v) * camera.width + u] = rh.hit.instID[0];
      }
    }
    raw.keep();
  }
  set_rates(state, camera, "rays/s");
}

// The same rays as 4x4 packets through rtcIntersect16 (Embree picks the widest SIMD the
// CPU has), to see what packets would gain over rtcIntersect1 for primary rays.
void BM_Render_RawEmbree16(benchmark::State& state) {
  BinScene bin(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!bin.ok) return state.SkipWithError(bin.error.c_str());
  const PinholeCamera& camera = bin.camera;
  if (camera.width % 4 != 0 || camera.height % 4 != 0) {
    return state.SkipWithError("image sides must be multiples of 4");
  }
  RawRays raw(camera);
  const RTCScene top = bin.scene.embree_scene();
  const int threads = threads_of(state);
  for (auto _ : state) {
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
    for (int by = 0; by < camera.height / 4; ++by) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      alignas(64) int valid[16];
      for (int& lane : valid) lane = -1;
      for (int bx = 0; bx < camera.width / 4; ++bx) {
        alignas(64) RTCRayHit16 rh;
        for (int k = 0; k < 16; ++k) {
          set_primary_ray(rh, k, raw.dx[4 * bx + k % 4], raw.dy[4 * by + k / 4]);
        }
        rtcIntersect16(valid, top, &context, &rh);
        for (int k = 0; k < 16; ++k) {
          const size_t pixel = size_t(4 * by + k / 4) * camera.width + 4 * bx + k % 4;
          raw.depth[pixel] = rh.ray.tfar[k];
          raw.instance[pixel] = rh.hit.instID[0][k];
        }
      }
    }
    raw.keep();
  }
  set_rates(state, camera, "rays/s");
}

// Each instance's amodal mask (one-instance scenes, within its projected box).
void BM_Render_AmodalMasks(benchmark::State& state) {
  BinScene bin(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!bin.ok) return state.SkipWithError(bin.error.c_str());
  const RaycastOptions options = raycast_options(state);
  for (auto _ : state) {
    std::vector<cv::Mat> masks = amodal_masks(bin.scene, bin.camera, options);
    benchmark::DoNotOptimize(masks.data());
  }
  set_rates(state, bin.camera, "pixels/s");
}

// shade() on a ray-cast image: one light, hard shadows (range 3 = 0: one shadow ray per
// lit pixel) or soft shadows (range 3 shadow rays per lit pixel over a 40 mm disc), plus
// the camera light (no shadow rays). Pixels/s; the primary rays are not included.
void BM_Render_Shade(benchmark::State& state) {
  BinScene bin(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  if (!bin.ok) return state.SkipWithError(bin.error.c_str());
  RaycastOptions raycast_options;
  raycast_options.threads = threads_of(state);
  const RaycastImages images = raycast(bin.scene, bin.camera, raycast_options);
  ShadingOptions options;
  options.threads = threads_of(state);
  options.camera_light = true;
  options.lights[0].position = {-300.0f, -600.0f, 0.0f};
  const int samples = static_cast<int>(state.range(3));
  options.lights[0].radius = samples > 0 ? 40.0f : 0.0f;
  options.shadow_samples = std::max(samples, 1);
  for (auto _ : state) {
    cv::Mat rgb = shade(bin.scene, images, options);
    benchmark::DoNotOptimize(rgb.data);
  }
  set_rates(state, bin.camera, "pixels/s");
  state.SetLabel(std::to_string(bin.camera.width) + "x" + std::to_string(bin.camera.height) + ", " +
                 std::to_string(threads_of(state)) + " thread(s), " +
                 (samples > 0 ? std::to_string(samples) + " shadow rays/pixel" : "hard shadows"));
}

// Reading T-LESS obj_02 (82 114 triangles): our STL reader, joining, crease normals, diameter.
void BM_Render_LoadMesh(benchmark::State& state) {
  for (auto _ : state) {
    try {
      Mesh mesh = load_mesh(tless_path("02"));
      benchmark::DoNotOptimize(mesh.diameter);
    } catch (const std::exception& e) {
      return state.SkipWithError(e.what());
    }
  }
}

// Sizes (the detector's 300x300 input and a 1280x960 camera) x threads (1 and all: 0).
// 300x300 and 1280x960, one thread and all; wall-clock milliseconds.
void sizes_and_threads(benchmark::internal::Benchmark* b) {
  for (const auto& size : {std::pair<int, int>{300, 300}, {1280, 960}})
    for (int threads : {1, 0}) b->Args({size.first, size.second, threads});
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(BM_Render_Raycast)->Apply(sizes_and_threads);
BENCHMARK(BM_Render_RawEmbree1)->Apply(sizes_and_threads);
BENCHMARK(BM_Render_RawEmbree16)->Apply(sizes_and_threads);
BENCHMARK(BM_Render_AmodalMasks)->Apply(sizes_and_threads);
// Shading: both sizes, one thread and all, hard shadows and 8 soft-shadow rays.
BENCHMARK(BM_Render_Shade)
    ->ArgsProduct({{300}, {300}, {1, 0}, {0, 8}})
    ->ArgsProduct({{1280}, {960}, {1, 0}, {0, 8}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Render_LoadMesh)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace flexsight

// Google Benchmark suite of the scalar reference path: one matching-cost evaluation,
// each PatchMatch stage on a full level, and the whole matcher, over image size x
// disparity range x window. Counters: pixels/s and plane-cost evaluations/s.
#include <benchmark/benchmark.h>

#include <limits>
#include <opencv2/imgproc.hpp>

#include "fallback/image_pyramid.h"
#include "fallback/patchmatch_reference.h"
#include "fallback/weight_table.h"
#include "host/stereo_pipeline.h"

namespace flexsight {
namespace {

// A random but spatially smooth RGB8 image: PatchMatch behaves on it as on texture.
cv::Mat textured_image(int width, int height) {
  cv::setRNGSeed(7);
  cv::Mat noise(height / 2 + 1, width / 2 + 1, CV_8UC3);
  cv::randu(noise, cv::Scalar::all(0), cv::Scalar::all(255));
  cv::Mat image;
  cv::resize(noise, image, cv::Size(width, height), 0, 0, cv::INTER_LINEAR);
  return image;
}

struct LevelFixture {
  ViewImage views[2];
  std::vector<float> weights = make_support_weight_table(10.0f);
  LevelInputs in;
  PlaneField fields[2];

  LevelFixture(int width, int height, int ndisp, int window) {
    cv::Mat left = textured_image(width, height);
    cv::Mat right;
    cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -ndisp / 3, 0, 1, 0);
    cv::warpAffine(left, right, shift, left.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
    views[0] = make_view_image(left);
    views[1] = make_view_image(right);
    in.views[0] = &views[0];
    in.views[1] = &views[1];
    in.weights = weights.data();
    in.cost = {window / 2, 2, 0.9f, 1.0f - 0.9f, 10.0f, 2.0f};
    in.ndisp = ndisp;
    in.seed = 1;
    in.threads = 0;
    for (int view = 0; view < 2; ++view) init_random_planes(in, view, 0, fields[view]);
  }
};

void set_counters(benchmark::State& state, double pixels_per_iteration,
                  double evaluations_per_iteration) {
  state.counters["pixels/s"] = benchmark::Counter(pixels_per_iteration * state.iterations(),
                                                  benchmark::Counter::kIsRate);
  if (evaluations_per_iteration > 0) {
    state.counters["evals/s"] = benchmark::Counter(
        evaluations_per_iteration * state.iterations(), benchmark::Counter::kIsRate);
  }
}

void BM_PlaneCost(benchmark::State& state) {
  LevelFixture f(320, 240, 64, static_cast<int>(state.range(0)));
  const ViewImage& l = f.views[0];
  const ViewImage& r = f.views[1];
  int x = 0;
  for (auto _ : state) {
    x = (x + 7) % l.width;
    benchmark::DoNotOptimize(pms_plane_cost(
        l.color.data(), l.gradient.data(), r.color.data(), r.gradient.data(), f.weights.data(),
        l.width, l.height, f.in.cost, x, 120, 0.01f, 0.0f, 20.0f, -1.0f,
        std::numeric_limits<float>::max()));
  }
  set_counters(state, 1, 1);
}
BENCHMARK(BM_PlaneCost)->Arg(11)->Arg(21)->Arg(35);

void BM_PropagateSpatial(benchmark::State& state) {
  LevelFixture f(static_cast<int>(state.range(0)), static_cast<int>(state.range(0)) * 2 / 3,
                 static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
  f.in.threads = 1;
  for (auto _ : state) {
    PlaneField field = f.fields[0];
    propagate_spatial(f.in, 0, 0, field);
    benchmark::DoNotOptimize(field.cost.data());
  }
  const double half = f.fields[0].pixels() / 2.0;
  set_counters(state, half, half * PMS_SPATIAL_CANDIDATES);
}
BENCHMARK(BM_PropagateSpatial)
    ->ArgsProduct({{96, 192}, {32, 64}, {11, 35}})
    ->Unit(benchmark::kMillisecond);

void BM_RefineRandom(benchmark::State& state) {
  LevelFixture f(static_cast<int>(state.range(0)), static_cast<int>(state.range(0)) * 2 / 3,
                 static_cast<int>(state.range(1)), static_cast<int>(state.range(2)));
  f.in.threads = 1;
  SearchSchedule schedule{0.5f * f.in.ndisp, 1.0f, 0.25f, 2.0f, 2.0f};
  for (auto _ : state) {
    PlaneField field = f.fields[0];
    refine_random(f.in, 0, 0, 1, schedule, nullptr, field);
    benchmark::DoNotOptimize(field.cost.data());
  }
  const double half = f.fields[0].pixels() / 2.0;
  set_counters(state, half,
               half * pms_search_trial_count(schedule.initial_range, schedule.min_range));
}
BENCHMARK(BM_RefineRandom)
    ->ArgsProduct({{96, 192}, {32, 64}, {11, 35}})
    ->Unit(benchmark::kMillisecond);

void BM_WholeMatcher(benchmark::State& state) {
  const int width = static_cast<int>(state.range(0));
  cv::Mat left = textured_image(width, width * 2 / 3);
  cv::Mat right;
  cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -10, 0, 1, 0);
  cv::warpAffine(left, right, shift, left.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  StereoParams params;
  params.ndisp = 32;
  params.method = state.range(1) == 0 ? StereoMethod::PPMS : StereoMethod::PMS;
  for (auto _ : state) {
    StereoResult result = run_stereo(left, right, params);
    benchmark::DoNotOptimize(result.disparity.data);
  }
  state.SetLabel(method_name(params.method));
  set_counters(state, static_cast<double>(left.total()), 0);
}
BENCHMARK(BM_WholeMatcher)
    ->ArgsProduct({{160, 320}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);

}  // namespace
}  // namespace flexsight

BENCHMARK_MAIN();

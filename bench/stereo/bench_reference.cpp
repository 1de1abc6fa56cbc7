// Google Benchmark suite of the scalar reference path (fallback/), on every core: the
// stages of bench_opencl.cpp that have a reference function, under the same names and
// arguments and on the same inputs (tests/stereo/kernel_cases.h), so that a report can put the
// two side by side; plus one matching-cost evaluation. An iteration's time is the
// stage call's wall-clock time (UseManualTime): resetting its inputs is not counted.
#include <benchmark/benchmark.h>

#include <chrono>
#include <limits>

#include "bench/stereo/bench_support.h"
#include "fallback/stereo/postprocess_reference.h"
#include "host/stereo/stereo_pipeline.h"

namespace flexsight::bench {
namespace {

using testing_support::ReferenceLevel;

// Per iteration: `reset` (untimed: restores the inputs the stage overwrites), then
// `call`, timed by the wall clock (the reference spreads rows over OpenMP threads, so
// the main thread's CPU time would undercount).
template <typename Reset, typename Call>
void time_on_host(benchmark::State& state, const Reset& reset, const Call& call) {
  using Clock = std::chrono::steady_clock;
  for (auto _ : state) {
    reset();
    const auto start = Clock::now();
    call();
    state.SetIterationTime(std::chrono::duration<double>(Clock::now() - start).count());
  }
}

template <typename Call>
void time_on_host(benchmark::State& state, const Call& call) {
  time_on_host(state, [] {}, call);
}

ReferenceLevel& fixture(const LevelCase& c, bool advanced = false) {
  return cached_fixture<ReferenceLevel>(c, advanced);
}

// The checkerboard stages run both parities of the left view: every pixel once. Per
// iteration the field is reset to `f`'s left field, then `stage(parity, field)` runs
// for both parities.
template <typename Stage>
void time_both_parities(benchmark::State& state, const ReferenceLevel& f, const Stage& stage) {
  PlaneField field;
  time_on_host(
      state, [&] { field = f.fields[PMS_VIEW_LEFT]; },
      [&] {
        for (int parity = 0; parity < 2; ++parity) stage(parity, field);
      });
}

// ------------------------------------------------------------------ pyramid

void compute_gradient(benchmark::State& state) {
  const LevelCase c = case_of(state);
  ViewImage image = fixture(c).images[PMS_VIEW_LEFT];
  time_on_host(state, [&] { flexsight::compute_gradient(image); });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kComputeGradientCost));
}

// Colour and gradient of the next level (the OpenCL path's downsample_color, then
// compute_gradient).
void downsample(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const ViewImage& fine = fixture(c).images[PMS_VIEW_LEFT];
  time_on_host(state, [&] { benchmark::DoNotOptimize(flexsight::downsample(fine)); });
  set_work_counters(state, downsample_work(c.width, c.height));
}

// ---------------------------------------------------------- PatchMatch stages

void init_random_planes(benchmark::State& state) {
  const LevelCase c = case_of(state);
  ReferenceLevel& f = fixture(c);
  PlaneField field;
  time_on_host(state, [&] { flexsight::init_random_planes(f.in, PMS_VIEW_LEFT, 0, field); });
  set_work_counters(state, init_random_planes_work(c.width, c.height, f.in.cost));
}

void evaluate_costs(benchmark::State& state) {
  const LevelCase c = case_of(state);
  ReferenceLevel& f = fixture(c, true);
  PlaneField field = f.fields[PMS_VIEW_LEFT];
  time_on_host(state, [&] { flexsight::evaluate_costs(f.in, PMS_VIEW_LEFT, field); });
  set_work_counters(state, evaluate_costs_work(c.width, c.height, f.in.cost));
}

// The checkerboard stages run both parities of the left view: every pixel once. No
// confidence (the coarsest level): every pixel tries all the spatial candidates.
void propagate_spatial(benchmark::State& state) {
  const LevelCase c = case_of(state);
  ReferenceLevel& f = fixture(c);
  const SearchSchedule schedule = testing_support::search_schedule(c.ndisp);
  time_both_parities(state, f, [&](int parity, PlaneField& field) {
    flexsight::propagate_spatial(f.in, PMS_VIEW_LEFT, parity, schedule, nullptr, field);
  });
  set_work_counters(state, propagate_spatial_work(c.width, c.height, f.in.cost));
}

void propagate_view(benchmark::State& state) {
  const LevelCase c = case_of(state);
  ReferenceLevel& f = fixture(c, true);
  time_both_parities(state, f, [&](int parity, PlaneField& field) {
    flexsight::propagate_view(f.in, PMS_VIEW_LEFT, parity, SearchSchedule{}, nullptr,
                              f.fields[PMS_VIEW_RIGHT], field);
  });
  set_work_counters(state, propagate_view_work(c.width, c.height, f.in.cost));
}

void refine_random(benchmark::State& state) {
  const LevelCase c = case_of(state);
  ReferenceLevel& f = fixture(c, true);
  const SearchSchedule schedule = testing_support::search_schedule(c.ndisp);
  time_both_parities(state, f, [&](int parity, PlaneField& field) {
    flexsight::refine_random(f.in, PMS_VIEW_LEFT, parity, 5, schedule, nullptr, field);
  });
  set_work_counters(state, refine_random_work(c.width, c.height, f.in.cost, schedule));
}

void carry_planes_to_finer(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const PlaneField& coarse = fixture(coarser_case(c)).fields[PMS_VIEW_LEFT];
  PlaneField fine;
  fine.resize(c.width, c.height);
  time_on_host(state, [&] { flexsight::carry_planes_to_finer(coarse, fine); });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kCarryPlanesToFinerCost));
}

void upsample_nearest(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const LevelCase half = coarser_case(c);
  const std::vector<float> coarse =
      testing_support::random_confidence(half.width * half.height, c.seed);
  time_on_host(state, [&] {
    benchmark::DoNotOptimize(
        flexsight::upsample_nearest(coarse, half.width, half.height, c.width, c.height));
  });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kUpsampleNearestCost));
}

void plane_disparities(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const PlaneField& field = fixture(c).fields[PMS_VIEW_LEFT];
  time_on_host(state, [&] {
    benchmark::DoNotOptimize(flexsight::plane_disparities(field, reference_threads()));
  });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kPlaneDisparitiesCost));
}

void lr_confidence(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const testing_support::DisparityPair pair = disparities_of(c);
  time_on_host(state, [&] {
    benchmark::DoNotOptimize(flexsight::lr_confidence(pair.left, pair.right, c.width, c.height,
                                                      PMS_VIEW_LEFT, reference_threads()));
  });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kLrConfidenceCost));
}

// --------------------------------------------------------------- post-processing

void left_right_check(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const testing_support::DisparityPair pair = disparities_of(c);
  time_on_host(state, [&] {
    benchmark::DoNotOptimize(flexsight::left_right_check(pair.left, pair.right, c.width,
                                                         c.height, PMS_VIEW_LEFT, kLrTolerance,
                                                         reference_threads()));
  });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kLeftRightCheckCost));
}

void fill_inconsistent(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const std::vector<std::uint8_t> flags =
      testing_support::random_consistency(c.width, c.height, c.seed);
  const std::vector<float>& planes = fixture(c).fields[PMS_VIEW_LEFT].planes;
  time_on_host(state, [&] {
    benchmark::DoNotOptimize(
        flexsight::fill_inconsistent(planes, flags, c.width, c.height,
                                     StereoParams().fill_max_extrapolation, reference_threads()));
  });
  set_work_counters(state, fill_inconsistent_work(c.width, c.height, flags));
}

void weighted_median_filled(benchmark::State& state) {
  const LevelCase c = case_of(state);
  ReferenceLevel& f = fixture(c);
  const testing_support::MedianInputs m = testing_support::median_inputs(f, c);
  time_on_host(state, [&] {
    benchmark::DoNotOptimize(flexsight::weighted_median_filled(
        m.disparity, m.consistent, f.images[PMS_VIEW_LEFT], m.weights.data(), m.radius, m.step,
        m.background_margin, reference_threads()));
  });
  set_work_counters(state, weighted_median_filled_work(c, m));
}

// The final median over every pixel, with the default window.
void weighted_median_all(benchmark::State& state) {
  const LevelCase c = case_of(state);
  ReferenceLevel& f = fixture(c);
  const testing_support::MedianInputs m = testing_support::median_inputs(f, c);
  time_on_host(state, [&] {
    benchmark::DoNotOptimize(
        flexsight::weighted_median_all(m.disparity, f.images[PMS_VIEW_LEFT], m.weights.data(),
                                       kFinalMedianRadius, reference_threads()));
  });
  set_work_counters(state, weighted_median_all_work(c.width, c.height, kFinalMedianRadius));
}

// ------------------------------------------------------------ the whole matcher

void whole_matcher(benchmark::State& state, StereoMethod method) {
  const LevelCase c = case_of(state);
  const testing_support::TexturedPair pair = testing_support::textured_pair(c);
  const StereoParams params = matcher_params(c, method);
  time_on_host(state, [&] {
    benchmark::DoNotOptimize(run_stereo(pair.left, pair.right, params).disparity.data);
  });
  set_work_counters(state, matcher_work(params, c.width, c.height));
}

// ------------------------------------------------------ one cost evaluation

// pms_plane_cost alone at inner pixels of a 320x240 level, one thread: the unit of
// work that evals/s counts, with a full window of (2 (radius / step) + 1)^2 samples.
void plane_cost(benchmark::State& state) {
  const LevelCase c = testing_support::benchmark_case(320, testing_support::kDefaultNdisp,
                                                      static_cast<int>(state.range(0)));
  const ReferenceLevel& f = fixture(c);
  const ViewImage& l = f.images[PMS_VIEW_LEFT];
  const ViewImage& r = f.images[PMS_VIEW_RIGHT];
  const int radius = f.in.cost.radius;
  const int py = c.height / 2;
  int x = 0;
  for (auto _ : state) {
    x = (x + 7) % (l.width - 2 * radius);
    benchmark::DoNotOptimize(pms_plane_cost(
        l.color.data(), l.gradient.data(), r.color.data(), r.gradient.data(), f.weights.data(),
        l.width, l.height, f.in.cost, radius + x, py, 0.01f, 0.0f, 20.0f, -1.0f,
        std::numeric_limits<float>::max()));
  }
  const int side = 2 * (radius / c.step) + 1;
  Work work;
  work.evaluations = 1;
  work.flops = side * side * kCostFlopsPerSample;
  work.bytes = side * side * kCostBytesPerSample;
  set_work_counters(state, work);
  state.SetLabel("one inner pixel");
}

void matcher_ppms(benchmark::State& state) { whole_matcher(state, StereoMethod::PPMS); }
void matcher_pms(benchmark::State& state) { whole_matcher(state, StereoMethod::PMS); }

void register_all() {
#define FLEXSIGHT_REGISTER(name, ...) register_kernel(#name, name);
  FLEXSIGHT_STEREO_STAGES(FLEXSIGHT_REGISTER)
#undef FLEXSIGHT_REGISTER
  benchmark::RegisterBenchmark("plane_cost", plane_cost)
      ->ArgName("window")
      ->Arg(11)
      ->Arg(21)
      ->Arg(35);
}

}  // namespace
}  // namespace flexsight::bench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::AddCustomContext("reference_threads",
                              std::to_string(flexsight::bench::reference_threads()));
  benchmark::AddCustomContext("timing", "wall clock of the stage call");
  flexsight::bench::register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

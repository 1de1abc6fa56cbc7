// Google Benchmark suite of the OpenCL path: every OpenClStages method and the whole
// matcher (PPMS and PMS), on the inputs the byte-for-byte tests use
// (tests/stereo/kernel_cases.h), over image size x disparity range x window. An iteration's
// time is the device time of the kernels it launched, summed from their OpenCL
// profiling events (UseManualTime): uploads, host work and the resetting of inputs
// between iterations are not counted. The same benchmarks of the reference path are
// in bench_reference.cpp, with the same names and arguments.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <string>

#include "bench/stereo/bench_support.h"
#include "host/stereo/opencl_matcher.h"
#include "tests/stereo/opencl/device_fixture.h"

namespace flexsight::bench {
namespace {

using opencl::Buffer;
using opencl::DeviceField;
using opencl::DeviceView;
using opencl::KernelProfiler;
using opencl::KernelTiming;
using opencl::OpenClStages;
using opencl::test::guarded;
using opencl::test::LevelFixture;
using opencl::test::upload;

KernelProfiler& profiler() {
  static KernelProfiler shared;
  return shared;
}

// The stages on the tests' device context, recording every launch's event.
OpenClStages& profiled_stages() {
  static OpenClStages shared(opencl::test::context(), &profiler());
  return shared;
}

double device_seconds(const std::vector<KernelTiming>& timings) {
  double seconds = 0;
  for (const KernelTiming& t : timings) seconds += t.seconds;
  return seconds;
}

// Per iteration: `reset` (untimed: restores the inputs the stage overwrites), then
// `launch`, timed by its kernels' device time.
template <typename Reset, typename Launch>
void time_on_device(benchmark::State& state, const Reset& reset, const Launch& launch) {
  OpenClStages& stages = profiled_stages();
  for (auto _ : state) {
    reset();
    profiler().clear();
    launch(stages);
    state.SetIterationTime(device_seconds(profiler().summary()));
  }
}

template <typename Launch>
void time_on_device(benchmark::State& state, const Launch& launch) {
  time_on_device(state, [] {}, launch);
}

LevelFixture& fixture(const LevelCase& c, bool advanced = false) {
  return cached_fixture<LevelFixture>(c, advanced);
}

void restore(DeviceField& device, const PlaneField& host) {
  device.planes.write(host.planes);
  device.cost.write(host.cost);
}

// The checkerboard stages run both parities of the left view: every pixel once. Per
// iteration the device field is restored to `start`, then `stage(s, parity, field)`
// runs for both parities.
template <typename Stage>
void time_both_parities(benchmark::State& state, const PlaneField& start, const Stage& stage) {
  DeviceField field = upload(start, "field");
  time_on_device(
      state, [&] { restore(field, start); },
      [&](OpenClStages& s) {
        for (int parity = 0; parity < 2; ++parity) stage(s, parity, field);
      });
}

// A case's left and right disparity maps (disparities_of), on the device.
struct DeviceDisparities {
  Buffer<float> left;
  Buffer<float> right;
};

DeviceDisparities device_disparities(const LevelCase& c) {
  const testing_support::DisparityPair pair = disparities_of(c);
  return {guarded(pair.left, "left"), guarded(pair.right, "right")};
}

// ------------------------------------------------------------------ pyramid

// The fixture's left view downsampled into the next level's view: its parity, and with
// `with_gradient` its gradient too.
void time_downsample(benchmark::State& state, bool with_gradient) {
  const LevelCase c = case_of(state);
  LevelFixture& f = fixture(c);
  const int w = (c.width + 1) / 2;
  const int h = (c.height + 1) / 2;
  DeviceView coarse{w, h, guarded(std::vector<float>(4 * w * h), "coarse colour"),
                    guarded(std::vector<float>(2 * w * h), "coarse gradient")};
  time_on_device(state, [&](OpenClStages& s) {
    s.downsample_color(f.device_images[PMS_VIEW_LEFT], coarse);
    if (with_gradient) s.compute_gradient(coarse);
  });
  set_work_counters(state, with_gradient ? downsample_work(c.width, c.height)
                                         : downsample_color_work(c.width, c.height));
}

void downsample_color(benchmark::State& state) { time_downsample(state, false); }

void compute_gradient(benchmark::State& state) {
  const LevelCase c = case_of(state);
  LevelFixture& f = fixture(c);
  // Rewrites the gradient the fixture already holds, with the same bytes.
  time_on_device(state, [&](OpenClStages& s) { s.compute_gradient(f.device_images[0]); });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kComputeGradientCost));
}

// Rewrites the left view's records the fixture already holds, with the same bytes.
void pack_match_samples(benchmark::State& state) {
  const LevelCase c = case_of(state);
  LevelFixture& f = fixture(c);
  time_on_device(state, [&](OpenClStages& s) {
    s.pack_match_samples(f.device_images[PMS_VIEW_LEFT], f.device_match[PMS_VIEW_LEFT]);
  });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kPackMatchSamplesCost));
}

// The reference's downsample: both launches of a pyramid level.
void downsample(benchmark::State& state) { time_downsample(state, true); }

// ---------------------------------------------------------- PatchMatch stages

void init_random_planes(benchmark::State& state) {
  const LevelCase c = case_of(state);
  LevelFixture& f = fixture(c);
  DeviceField field = upload(f.fields[PMS_VIEW_LEFT], "field");
  time_on_device(state, [&](OpenClStages& s) {
    s.init_random_planes(f.device_in, PMS_VIEW_LEFT, 0, field);
  });
  set_work_counters(state, init_random_planes_work(c.width, c.height, f.in.cost));
}

void evaluate_costs(benchmark::State& state) {
  const LevelCase c = case_of(state);
  LevelFixture& f = fixture(c, true);
  DeviceField field = upload(f.fields[PMS_VIEW_LEFT], "field");
  time_on_device(state, [&](OpenClStages& s) {
    s.evaluate_costs(f.device_in, PMS_VIEW_LEFT, field);
  });
  set_work_counters(state, evaluate_costs_work(c.width, c.height, f.in.cost));
}

// The checkerboard stages run both parities of the left view: every pixel once. No
// confidence (the coarsest level): every pixel tries all the spatial candidates.
void propagate_spatial(benchmark::State& state) {
  const LevelCase c = case_of(state);
  LevelFixture& f = fixture(c);
  const SearchSchedule schedule = testing_support::search_schedule(c.ndisp);
  time_both_parities(state, f.fields[PMS_VIEW_LEFT],
                    [&](OpenClStages& s, int parity, DeviceField& field) {
                      s.propagate_spatial(f.device_in, PMS_VIEW_LEFT, parity, schedule, nullptr,
                                          field);
                    });
  set_work_counters(state, propagate_spatial_work(c.width, c.height, f.in.cost));
}

void propagate_view(benchmark::State& state) {
  const LevelCase c = case_of(state);
  LevelFixture& f = fixture(c, true);
  const DeviceField other = upload(f.fields[PMS_VIEW_RIGHT], "other field");
  time_both_parities(state, f.fields[PMS_VIEW_LEFT],
                    [&](OpenClStages& s, int parity, DeviceField& field) {
                      s.propagate_view(f.device_in, PMS_VIEW_LEFT, parity, SearchSchedule{},
                                       nullptr, other, field);
                    });
  set_work_counters(state, propagate_view_work(c.width, c.height, f.in.cost));
}

void refine_random(benchmark::State& state) {
  const LevelCase c = case_of(state);
  LevelFixture& f = fixture(c, true);
  const SearchSchedule schedule = testing_support::search_schedule(c.ndisp);
  time_both_parities(state, f.fields[PMS_VIEW_LEFT],
                    [&](OpenClStages& s, int parity, DeviceField& field) {
                      s.refine_random(f.device_in, PMS_VIEW_LEFT, parity, 5, schedule, nullptr,
                                      field);
                    });
  set_work_counters(state, refine_random_work(c.width, c.height, f.in.cost, schedule));
}

void carry_planes_to_finer(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const DeviceField coarse = upload(fixture(coarser_case(c)).fields[PMS_VIEW_LEFT], "coarse");
  const size_t pixels = static_cast<size_t>(c.width) * c.height;
  DeviceField fine{c.width, c.height, guarded(std::vector<float>(4 * pixels), "fine planes"),
                   guarded(std::vector<float>(pixels), "fine cost")};
  time_on_device(state, [&](OpenClStages& s) { s.carry_planes_to_finer(coarse, fine); });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kCarryPlanesToFinerCost));
}

void upsample_nearest(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const LevelCase half = coarser_case(c);
  const Buffer<float> coarse =
      guarded(testing_support::random_confidence(half.width * half.height, c.seed), "coarse");
  Buffer<float> fine = guarded(std::vector<float>(c.width * c.height), "fine");
  time_on_device(state, [&](OpenClStages& s) {
    s.upsample_nearest(coarse, half.width, half.height, fine, c.width, c.height);
  });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kUpsampleNearestCost));
}

void plane_disparities(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const DeviceField field = upload(fixture(c).fields[PMS_VIEW_LEFT], "field");
  Buffer<float> disparity = guarded(std::vector<float>(c.width * c.height), "disparity");
  time_on_device(state, [&](OpenClStages& s) { s.plane_disparities(field, disparity); });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kPlaneDisparitiesCost));
}

void lr_confidence(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const DeviceDisparities d = device_disparities(c);
  Buffer<float> confidence = guarded(std::vector<float>(c.width * c.height), "confidence");
  time_on_device(state, [&](OpenClStages& s) {
    s.lr_confidence(d.left, d.right, c.width, c.height, PMS_VIEW_LEFT, confidence);
  });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kLrConfidenceCost));
}

// --------------------------------------------------------------- post-processing

void left_right_check(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const DeviceDisparities d = device_disparities(c);
  Buffer<std::uint8_t> consistent =
      guarded(std::vector<std::uint8_t>(c.width * c.height), "consistent");
  time_on_device(state, [&](OpenClStages& s) {
    s.left_right_check(d.left, d.right, c.width, c.height, PMS_VIEW_LEFT, kLrTolerance,
                       consistent);
  });
  set_work_counters(state, pixel_stage_work(c.width, c.height, kLeftRightCheckCost));
}

void fill_inconsistent(benchmark::State& state) {
  const LevelCase c = case_of(state);
  const std::vector<std::uint8_t> flags =
      testing_support::random_consistency(c.width, c.height, c.seed);
  const Buffer<float> planes = guarded(fixture(c).fields[PMS_VIEW_LEFT].planes, "planes");
  const Buffer<std::uint8_t> consistent = guarded(flags, "consistent");
  Buffer<float> filled = guarded(std::vector<float>(4 * flags.size()), "filled");
  time_on_device(state, [&](OpenClStages& s) {
    s.fill_inconsistent(planes, consistent, c.width, c.height,
                        StereoParams().fill_max_extrapolation, filled);
  });
  set_work_counters(state, fill_inconsistent_work(c.width, c.height, flags));
}

void weighted_median_filled(benchmark::State& state) {
  const LevelCase c = case_of(state);
  LevelFixture& f = fixture(c);
  const testing_support::MedianInputs m = testing_support::median_inputs(f, c);
  const Buffer<float> disparity = guarded(m.disparity, "disparity");
  const Buffer<std::uint8_t> consistent = guarded(m.consistent, "consistent");
  const Buffer<float> weights = guarded(m.weights, "weights");
  Buffer<float> filtered = guarded(std::vector<float>(m.disparity.size()), "filtered");
  time_on_device(state, [&](OpenClStages& s) {
    s.weighted_median_filled(disparity, consistent, f.device_images[PMS_VIEW_LEFT], weights,
                             m.radius, m.step, m.background_margin, filtered);
  });
  set_work_counters(state, weighted_median_filled_work(c, m));
}

// The final median over every pixel, with the default window.
void weighted_median_all(benchmark::State& state) {
  const LevelCase c = case_of(state);
  LevelFixture& f = fixture(c);
  const testing_support::MedianInputs m = testing_support::median_inputs(f, c);
  const Buffer<float> disparity = guarded(m.disparity, "disparity");
  const Buffer<float> weights = guarded(m.weights, "weights");
  Buffer<float> filtered = guarded(std::vector<float>(m.disparity.size()), "filtered");
  time_on_device(state, [&](OpenClStages& s) {
    s.weighted_median_all(disparity, f.device_images[PMS_VIEW_LEFT], weights, kFinalMedianRadius,
                          filtered);
  });
  set_work_counters(state, weighted_median_all_work(c.width, c.height, kFinalMedianRadius));
}

// ------------------------------------------------------------ the whole matcher

// Built once: building the programs takes seconds. It selects the device the way the
// stages' context does ($FLEXSIGHT_OPENCL_DEVICE).
opencl::OpenClMatcher& matcher() {
  static opencl::OpenClMatcher shared([] {
    opencl::OpenClOptions options;
    const char* device = std::getenv("FLEXSIGHT_OPENCL_DEVICE");
    options.cl_device = device ? device : "";
    options.profile = true;
    return options;
  }());
  return shared;
}

// Timed like the stages (the sum of every kernel's device time); "wall_ms" adds the
// host's view of a run: uploads, reads, launches and waits included.
void whole_matcher(benchmark::State& state, StereoMethod method) {
  const LevelCase c = case_of(state);
  const testing_support::TexturedPair pair = testing_support::textured_pair(c);
  const StereoParams params = matcher_params(c, method);
  double wall_seconds = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    StereoResult result = matcher().run(pair.left, pair.right, params);
    wall_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(result.disparity.data);
    state.SetIterationTime(device_seconds(matcher().kernel_timings()));
  }
  set_work_counters(state, matcher_work(params, c.width, c.height));
  state.counters["wall_ms"] =
      benchmark::Counter(wall_seconds * 1e3, benchmark::Counter::kAvgIterations);
}

void matcher_ppms(benchmark::State& state) { whole_matcher(state, StereoMethod::PPMS); }
void matcher_pms(benchmark::State& state) { whole_matcher(state, StereoMethod::PMS); }

void register_all() {
#define FLEXSIGHT_REGISTER(name, ...) register_kernel(#name, name);
  FLEXSIGHT_STEREO_DEVICE_ONLY_STAGES(FLEXSIGHT_REGISTER)
  FLEXSIGHT_STEREO_STAGES(FLEXSIGHT_REGISTER)
#undef FLEXSIGHT_REGISTER
}

void add_device_context() {
  const opencl::DeviceInfo& device = opencl::test::context().device();
  benchmark::AddCustomContext("opencl_device", device.description());
  benchmark::AddCustomContext("opencl_driver", device.driver_version);
  benchmark::AddCustomContext("opencl_compute_units", std::to_string(device.compute_units));
  benchmark::AddCustomContext("opencl_matcher_device", matcher().device_description());
  benchmark::AddCustomContext("timing", "device time from OpenCL profiling events");
}

}  // namespace
}  // namespace flexsight::bench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  flexsight::bench::add_device_context();
  flexsight::bench::register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

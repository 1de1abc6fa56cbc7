#pragma once
// What the two benchmark suites share: each kernel's benchmark registered from its
// description in tests/stereo/kernel_cases.h (the same names and arguments in both suites, so
// that a report can pair an OpenCL run with its reference run), the case of an
// instance, the work counters of kernel_work_model.h and a cache of fixtures.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>

#include "bench/stereo/kernel_work_model.h"
#include "tests/stereo/kernel_cases.h"

namespace flexsight::bench {

using testing_support::LevelCase;

// The reference runs on every core, as the matcher runs it; the OpenCL driver too.
inline int reference_threads() { return omp_get_num_procs(); }

// The case of a benchmark instance, from its arguments (width, ndisp, window); labels
// the instance with the image size, which the arguments name by width only.
inline LevelCase case_of(benchmark::State& state) {
  const LevelCase c = testing_support::benchmark_case(static_cast<int>(state.range(0)),
                                                      static_cast<int>(state.range(1)),
                                                      static_cast<int>(state.range(2)));
  state.SetLabel(std::to_string(c.width) + "x" + std::to_string(c.height));
  return c;
}

// Rates of one iteration's work over the measured time; GFLOP/s and GB/s are scaled
// here so that the JSON holds the number a reader compares with a data sheet.
inline void set_work_counters(benchmark::State& state, const Work& work) {
  using benchmark::Counter;
  if (work.pixels > 0) {
    state.counters["pixels/s"] = Counter(work.pixels, Counter::kIsIterationInvariantRate);
  }
  if (work.evaluations > 0) {
    state.counters["evals/s"] = Counter(work.evaluations, Counter::kIsIterationInvariantRate);
  }
  state.counters["GFLOP/s"] = Counter(work.flops * 1e-9, Counter::kIsIterationInvariantRate);
  state.counters["GB/s"] = Counter(work.bytes * 1e-9, Counter::kIsIterationInvariantRate);
}

// Registers `run` as benchmark `name` over the arguments its description sweeps. Time
// is manual in both suites: each measures the stage alone, not the resetting of its
// inputs between iterations.
template <typename Run>
void register_kernel(const char* name, Run run) {
  const testing_support::KernelDescription kernel = testing_support::kernel_description(name);
  if (kernel.name == nullptr) {
    throw std::logic_error(std::string("no description of kernel '") + name +
                           "' in tests/stereo/kernel_cases.h");
  }
  benchmark::RegisterBenchmark(name, run)
      ->ArgsProduct(testing_support::benchmark_arguments(kernel))
      ->ArgNames({"width", "ndisp", "window"})
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
}

// The fixture of a case, from its initial planes or (`advanced`) after advance(), built
// on first use: building computes the reference's initial planes (seconds at the larger
// sizes), and Google Benchmark calls a benchmark function several times per instance.
template <typename Fixture>
Fixture& cached_fixture(const LevelCase& c, bool advanced = false) {
  static std::map<std::tuple<int, int, int, bool>, std::unique_ptr<Fixture>> cache;
  std::unique_ptr<Fixture>& slot = cache[{c.width, c.ndisp, c.window, advanced}];
  if (!slot) {
    slot = std::make_unique<Fixture>(c, reference_threads());
    if (advanced) testing_support::advance(*slot);
  }
  return *slot;
}

// The case half the size of `c` (its planes are carried to `c`'s size).
inline LevelCase coarser_case(const LevelCase& c) {
  return testing_support::benchmark_case(c.width / 2, c.ndisp, c.window);
}

// The left and right disparity maps the left/right stages of a case read.
inline testing_support::DisparityPair disparities_of(const LevelCase& c) {
  return testing_support::random_disparities(c.width, c.height, c.ndisp, c.seed);
}

constexpr float kLrTolerance = 1.0f;  // StereoParams::lr_tolerance

// The final median's radius, with the default window.
constexpr int kFinalMedianRadius = StereoParams{}.final_median_window / 2;

// The work of weighted_median_filled on a case's median inputs.
inline Work weighted_median_filled_work(const LevelCase& c,
                                        const testing_support::MedianInputs& m) {
  return weighted_median_filled_work(c.width, c.height, m.consistent, m.radius, m.step);
}

// The parameters of a whole-matcher benchmark: the defaults with the case's method,
// disparity range and window.
inline StereoParams matcher_params(const LevelCase& c, StereoMethod method) {
  StereoParams params;
  params.method = method;
  params.ndisp = c.ndisp;
  params.window = c.window;
  return params;
}

}  // namespace flexsight::bench

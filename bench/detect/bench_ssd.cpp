// Google Benchmark of SSD post-processing (decode, scores, per-class NMS, overall cut)
// at the detector's size, 1917 anchors x 23 classes (the T-LESS parts; 24 logit columns
// with the background), on
// the reference path and, where this build has OpenCL, on the device of
// $FLEXSIGHT_OPENCL_DEVICE (default: first GPU, else first device), in one process.
// Inputs are the tests' cases (tests/detect/ssd_cases.h):
//   Sparse  scores as a trained detector gives them: a few clusters above the threshold;
//   Random  logits uniform in [-4, 2]: 48 % of all (anchor, class) pairs above 0.3,
//           the worst case for the candidate ranking.
// Times are wall-clock per call, as the caller sees them (OpenCL: uploading the two
// output arrays, 7 kernels, reading the detections back); device_us is the sum of the
// kernels' device times from their profiling events. Run with
// --benchmark_repetitions=N to get medians.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "host/detect/ssd_postprocess.h"
#include "tests/detect/ssd_cases.h"

#if defined(FLEXSIGHT_HAVE_OPENCL)
#include "host/detect/opencl_ssd_postprocessor.h"
#include "host/runtime/cl_device.h"
#endif

namespace flexsight::bench {
namespace {

using testing_support::SsdCase;
using testing_support::SsdInputs;
using testing_support::SsdScene;

SsdCase bench_case(SsdScene scene, SsdScoreFunction function) {
  return testing_support::ssd_case(kSsdMobileNetV2AnchorCount, 23, scene, function);
}

void BM_SsdReference(benchmark::State& state, SsdCase c) {
  const SsdInputs in = testing_support::make_ssd_inputs(c);
  size_t detections = 0;
  for (auto _ : state) {
    const std::vector<Detection> found =
        ssd_postprocess_reference(in.outputs(), in.anchors, c.params);
    detections = found.size();
    benchmark::DoNotOptimize(found.data());
  }
  state.counters["detections"] = static_cast<double>(detections);
}

#if defined(FLEXSIGHT_HAVE_OPENCL)
std::shared_ptr<opencl::Context> bench_context() {
  static std::shared_ptr<opencl::Context> shared;
  if (!shared) {
    const char* selector = std::getenv("FLEXSIGHT_OPENCL_DEVICE");
    shared = std::make_shared<opencl::Context>(opencl::select_device(selector ? selector : ""));
  }
  return shared;
}

void BM_SsdOpenCl(benchmark::State& state, SsdCase c) {
  const SsdInputs in = testing_support::make_ssd_inputs(c);
  std::unique_ptr<opencl::OpenClSsdPostprocessor> post;
  try {
    post = std::make_unique<opencl::OpenClSsdPostprocessor>(bench_context(), in.anchors, true);
  } catch (const std::exception& error) {
    state.SkipWithError(error.what());
    return;
  }
  post->run(in.outputs(), c.params);  // warm-up: first launches, buffer allocation
  std::map<std::string, double> kernel_seconds;
  double device_seconds = 0;
  size_t detections = 0;
  for (auto _ : state) {
    detections = post->run(in.outputs(), c.params).size();
    for (const opencl::KernelTiming& t : post->kernel_timings()) {
      kernel_seconds[t.kernel] += t.seconds;
      device_seconds += t.seconds;
    }
  }
  const double iterations = static_cast<double>(state.iterations());
  state.counters["detections"] = static_cast<double>(detections);
  state.counters["device_us"] = device_seconds / iterations * 1e6;
  for (const auto& [kernel, seconds] : kernel_seconds) {
    state.counters[kernel + "_us"] = seconds / iterations * 1e6;
  }
  state.SetLabel(post->device_description());
}
#endif

void register_benchmarks() {
  const struct {
    const char* name;
    SsdScene scene;
    SsdScoreFunction function;
  } cases[] = {
      {"Sparse_1917x23_sigmoid", SsdScene::Sparse, SsdScoreFunction::Sigmoid},
      {"Sparse_1917x23_softmax", SsdScene::Sparse, SsdScoreFunction::Softmax},
      {"Random_1917x23_sigmoid", SsdScene::Random, SsdScoreFunction::Sigmoid},
  };
  for (const auto& c : cases) {
    const SsdCase ssd = bench_case(c.scene, c.function);
    benchmark::RegisterBenchmark((std::string("BM_SsdReference/") + c.name).c_str(),
                                 BM_SsdReference, ssd)
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime();
#if defined(FLEXSIGHT_HAVE_OPENCL)
    benchmark::RegisterBenchmark((std::string("BM_SsdOpenCl/") + c.name).c_str(), BM_SsdOpenCl,
                                 ssd)
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime();
#endif
  }
}

}  // namespace
}  // namespace flexsight::bench

int main(int argc, char** argv) {
  flexsight::bench::register_benchmarks();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// Google Benchmark of the detector end to end (host/detect/ssd_detector.h): per image,
// resize to 300x300 and scale (preprocess), OpenCV DNN's forward, decode + scores + NMS
// (post-process), and each stage alone, on the model of $FLEXSIGHT_DETECT_MODEL, else the
// shipped one (default_detector_model_path()); without a model every benchmark reports
// the missing file and skips. The image: $FLEXSIGHT_DETECT_IMAGE, else the tests' fixture
// picture (317x241) resized to 640x480.
//
// The argument is OpenCV's thread count (cv::setNumThreads: the forward's layers and the
// resize); the post-processing runs on the reference path, or on OpenCL (the device of
// $FLEXSIGHT_OPENCL_DEVICE) in BM_DetectPostprocess/OpenCl. BM_DetectForward_DnnOpenCl
// runs the network on OpenCV DNN's OpenCL target: on a GPU, or (to measure it there) on
// PoCL with OPENCV_OPENCL_DEVICE=:CPU: OPENCV_DNN_OPENCL_ALLOW_ALL_DEVICES=1; elsewhere
// it reports why not. Run with --benchmark_repetitions=N for medians.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "host/detect/detector_model.h"
#include "host/detect/ssd_detector.h"

namespace flexsight::bench {
namespace {

std::string model_path() { return default_detector_model_path(); }

const cv::Mat& bench_image() {
  static const cv::Mat image = [] {
    const char* given = std::getenv("FLEXSIGHT_DETECT_IMAGE");
    if (given && *given) return cv::imread(given, cv::IMREAD_COLOR);
    cv::Mat fixture = cv::imread(FLEXSIGHT_TINY_SSD_IMAGE, cv::IMREAD_COLOR), resized;
    if (!fixture.empty()) cv::resize(fixture, resized, cv::Size(640, 480));
    return resized;
  }();
  return image;
}

// One detector per (post-processing path, DNN target), built on first use and kept: the
// load (network, kernels) is not what is measured. Null, with the reason, when the model
// or the image is missing or the path cannot start.
SsdDetector* detector(BackendKind kind, DnnTarget target, std::string* why) {
  static std::map<std::pair<BackendKind, DnnTarget>, std::unique_ptr<SsdDetector>> detectors;
  const auto key = std::make_pair(kind, target);
  if (detectors.count(key)) return detectors[key].get();
  const std::string path = model_path();
  if (!std::filesystem::exists(path)) {
    *why = "no detector model at " + path +
           ": set FLEXSIGHT_DETECT_MODEL to a model.onnx "
           "(with anchors.csv and labels.txt beside it)";
    return nullptr;
  }
  if (bench_image().empty()) {
    *why = "no image: FLEXSIGHT_DETECT_IMAGE does not name a readable image";
    return nullptr;
  }
  BackendOptions backend;
  backend.kind = kind;
  const char* device = std::getenv("FLEXSIGHT_OPENCL_DEVICE");
  if (kind == BackendKind::OpenCl && device) backend.cl_device = device;
  SsdDetectorOptions options;
  options.dnn_target = target;
  try {
    detectors[key] = std::make_unique<SsdDetector>(path, options, backend);
  } catch (const std::exception& error) {
    *why = error.what();
    return nullptr;
  }
  return detectors[key].get();
}

void add_context(benchmark::State& state, SsdDetector& d) {
  state.SetLabel(std::to_string(bench_image().cols) + "x" + std::to_string(bench_image().rows) +
                 " image, " + std::to_string(cv::getNumThreads()) + " OpenCV threads");
  state.counters["anchors"] = d.anchor_count();
  state.counters["classes"] = d.class_count();
}

// resize + forward + decode + NMS: what one image costs.
void BM_DetectEndToEnd(benchmark::State& state) {
  cv::setNumThreads(static_cast<int>(state.range(0)));
  std::string why;
  SsdDetector* d = detector(BackendKind::Reference, DnnTarget::Cpu, &why);
  if (!d) return state.SkipWithError(why.c_str());
  d->detect(bench_image());  // warm-up
  DetectionTimes sum, spent;
  size_t detections = 0;
  for (auto _ : state) {
    detections = d->detect(bench_image(), &spent).size();
    sum.preprocess += spent.preprocess;
    sum.forward += spent.forward;
    sum.postprocess += spent.postprocess;
  }
  const double n = static_cast<double>(state.iterations());
  state.SetItemsProcessed(state.iterations());  // items_per_second = images/s
  state.counters["preprocess_ms"] = sum.preprocess / n * 1e3;
  state.counters["forward_ms"] = sum.forward / n * 1e3;
  state.counters["postprocess_ms"] = sum.postprocess / n * 1e3;
  state.counters["detections"] = static_cast<double>(detections);
  add_context(state, *d);
}

void BM_DetectPreprocess(benchmark::State& state) {
  cv::setNumThreads(static_cast<int>(state.range(0)));
  std::string why;
  SsdDetector* d = detector(BackendKind::Reference, DnnTarget::Cpu, &why);
  if (!d) return state.SkipWithError(why.c_str());
  for (auto _ : state) benchmark::DoNotOptimize(d->preprocess(bench_image()).data);
  add_context(state, *d);
}

void forward_benchmark(benchmark::State& state, DnnTarget target) {
  cv::setNumThreads(static_cast<int>(state.range(0)));
  std::string why;
  SsdDetector* d = detector(BackendKind::Reference, target, &why);
  if (!d) return state.SkipWithError(why.c_str());
  const cv::Mat blob = d->preprocess(bench_image());
  d->forward(blob);  // warm-up (OpenCL: kernels built)
  for (auto _ : state) benchmark::DoNotOptimize(d->forward(blob).box_encodings.data);
  add_context(state, *d);
}

void BM_DetectForward(benchmark::State& state) { forward_benchmark(state, DnnTarget::Cpu); }
void BM_DetectForward_DnnOpenCl(benchmark::State& state) {
  forward_benchmark(state, DnnTarget::OpenCl);
}

void postprocess_benchmark(benchmark::State& state, BackendKind kind) {
  std::string why;
  SsdDetector* d = detector(kind, DnnTarget::Cpu, &why);
  if (!d) return state.SkipWithError(why.c_str());
  const SsdNetworkOutputs outputs = d->forward(d->preprocess(bench_image()));
  d->postprocess(outputs, bench_image().size());  // warm-up
  size_t detections = 0;
  for (auto _ : state) detections = d->postprocess(outputs, bench_image().size()).size();
  state.counters["detections"] = static_cast<double>(detections);
  state.SetLabel(d->planned());
}

void BM_DetectPostprocess_Reference(benchmark::State& state) {
  postprocess_benchmark(state, BackendKind::Reference);
}
void BM_DetectPostprocess_OpenCl(benchmark::State& state) {
  postprocess_benchmark(state, BackendKind::OpenCl);
}

BENCHMARK(BM_DetectEndToEnd)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DetectPreprocess)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DetectForward)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DetectForward_DnnOpenCl)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DetectPostprocess_Reference)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DetectPostprocess_OpenCl)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace flexsight::bench

BENCHMARK_MAIN();

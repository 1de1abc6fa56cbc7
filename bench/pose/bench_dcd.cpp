// Google Benchmark of the directional chamfer tensor (D2CO's defaults: 60 bins) on a
// synthetic image of overlapping shapes: building the tensor of a 160x160 box (a part's
// box in the pipeline) and of the whole 640x480 image, and the edge detection before
// it. Counters: edge pixels and cells (pixels x bins) per second.
#include <benchmark/benchmark.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "host/pose/dcd_tensor.h"

namespace flexsight {
namespace {

// Seeded rectangles, circles and lines of random grey levels on a mid-grey 640x480
// image: edges in every direction, corners and clutter.
cv::Mat shapes_image() {
  cv::Mat image(480, 640, CV_8UC1, cv::Scalar(128));
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> x(0, 639), y(0, 479), grey(0, 255), radius(5, 60);
  for (int i = 0; i < 60; ++i) {
    const cv::Scalar colour(grey(rng));
    switch (i % 3) {
      case 0:
        cv::rectangle(image, cv::Point(x(rng), y(rng)), cv::Point(x(rng), y(rng)), colour,
                      cv::FILLED);
        break;
      case 1: cv::circle(image, cv::Point(x(rng), y(rng)), radius(rng), colour, cv::FILLED); break;
      default: cv::line(image, cv::Point(x(rng), y(rng)), cv::Point(x(rng), y(rng)), colour, 3);
    }
  }
  return image;
}

// The box of the benchmark's size in the middle of the image.
cv::Rect centred_box(const benchmark::State& state) {
  const int width = static_cast<int>(state.range(0)), height = static_cast<int>(state.range(1));
  return cv::Rect((640 - width) / 2, (480 - height) / 2, width, height);
}

void BM_Dcd_DetectEdges(benchmark::State& state) {
  const cv::Mat image = shapes_image();
  const cv::Rect box = centred_box(state);
  for (auto _ : state) {
    const EdgeMap edges = detect_edges(image, box, DcdParams());
    benchmark::DoNotOptimize(edges.mask.data);
  }
  state.counters["pixels/s"] =
      benchmark::Counter(double(box.area()) * state.iterations(), benchmark::Counter::kIsRate);
}

void BM_Dcd_BuildTensor(benchmark::State& state) {
  const DcdParams params;
  const EdgeMap edges = detect_edges(shapes_image(), centred_box(state), params);
  for (auto _ : state) {
    const DcdTensor tensor(edges, params);
    benchmark::DoNotOptimize(tensor.layer(0).data);
  }
  state.counters["edge_pixels"] = cv::countNonZero(edges.mask);
  state.counters["cells/s"] =
      benchmark::Counter(double(edges.mask.total()) * params.orientation_bins * state.iterations(),
                         benchmark::Counter::kIsRate);
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Args({160, 160})->Args({640, 480})->ArgNames({"w", "h"});
  b->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(5)->ReportAggregatesOnly(true);
}

BENCHMARK(BM_Dcd_DetectEdges)->Apply(sizes);
BENCHMARK(BM_Dcd_BuildTensor)->Apply(sizes);

}  // namespace
}  // namespace flexsight

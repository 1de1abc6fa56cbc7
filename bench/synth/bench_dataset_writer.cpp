// Google Benchmark of what a generated image costs after rendering: encoding (JPEG
// rgb, 16-bit PNG depth, 8-bit PNG masks, COCO RLE) and writing through DatasetWriter,
// one thread, at 300x300 and 1280x960, on full-synthetic images of the default
// settings. With BM_Synth_FullSynthetic (bench_synth.cpp) it splits an image's time
// into rays, shading, compositing, annotations, encoding and writing.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/core/utility.hpp>
#include <string>
#include <vector>

#include "host/dataset/dataset_writer.h"
#include "host/synth/full_synthetic.h"

namespace flexsight {
namespace {

void BM_Synth_WriteImage(benchmark::State& state) {
  cv::setNumThreads(1);
  std::vector<AnnotatedImage> images;
  try {
    const PartLibrary parts = PartLibrary::load_folder(FLEXSIGHT_TLESS_CAD_DIR);
    const BackgroundLibrary backgrounds(FLEXSIGHT_BACKGROUNDS_DIR);
    FullSyntheticSettings settings;
    settings.width = static_cast<int>(state.range(0));
    settings.height = static_cast<int>(state.range(1));
    for (int i = 0; i < 8; ++i) {
      images.push_back(render_full_synthetic(settings, parts, backgrounds, 1, i));
    }
  } catch (const std::exception& e) {
    return state.SkipWithError(e.what());
  }
  const std::filesystem::path root = std::filesystem::temp_directory_path() /
                                     ("flexsight_bench_writer_" + std::to_string(::getpid()));
  std::filesystem::remove_all(root);
  double parts = 0.0;
  {
    DatasetWriter writer(root.string(), DatasetWriterOptions{});
    std::int64_t index = 0;
    for (auto _ : state) {
      AnnotatedImage image = images[index % images.size()];
      image.scene_id = static_cast<int>(index / 1000);
      image.im_id = static_cast<int>(index % 1000);
      writer.add(image, index++);
      parts += double(image.parts.size());
    }
  }
  std::uintmax_t bytes = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (entry.is_regular_file()) bytes += entry.file_size();
  }
  std::filesystem::remove_all(root);
  state.counters["images/s"] =
      benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["parts"] = benchmark::Counter(parts, benchmark::Counter::kAvgIterations);
  state.counters["kB/image"] =
      benchmark::Counter(double(bytes) / 1024.0, benchmark::Counter::kAvgIterations);
  state.SetLabel(std::to_string(state.range(0)) + "x" + std::to_string(state.range(1)) +
                 ", jpg + depth + masks, 1 thread");
}

BENCHMARK(BM_Synth_WriteImage)
    ->Args({300, 300})
    ->Args({1280, 960})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace flexsight

// Google Benchmark of the full-synthetic generator on the real T-LESS parts and
// backgrounds (FLEXSIGHT_TLESS_CAD_DIR, FLEXSIGHT_BACKGROUNDS_DIR), one thread, default
// settings (1-6 parts, shadows, flips, rotation, masks and depth), at the detector's
// 300x300 and at 1280x960. Each iteration renders the next image of the data set, so
// the figures are averages over different images; the iteration count is fixed, so that
// every repetition (and every build compared) renders the same images: their number of
// parts and their sizes vary a lot, and a few images would not be a fair sample. Counters:
// images/s, and per image the milliseconds of each stage (FullSyntheticStats), the parts
// kept and the poses cast.
#include <benchmark/benchmark.h>

#include <memory>
#include <opencv2/core/utility.hpp>
#include <string>

#include "host/synth/full_synthetic.h"

namespace flexsight {
namespace {

// The libraries, read once for every benchmark of the process.
struct Libraries {
  std::unique_ptr<PartLibrary> parts;
  std::unique_ptr<BackgroundLibrary> backgrounds;
  std::string error;
};

const Libraries& libraries() {
  static const Libraries loaded = [] {
    Libraries l;
    try {
      l.parts = std::make_unique<PartLibrary>(PartLibrary::load_folder(FLEXSIGHT_TLESS_CAD_DIR));
      l.backgrounds = std::make_unique<BackgroundLibrary>(FLEXSIGHT_BACKGROUNDS_DIR);
    } catch (const std::exception& e) {
      l.error = e.what();
    }
    return l;
  }();
  return loaded;
}

void BM_Synth_FullSynthetic(benchmark::State& state) {
  const Libraries& l = libraries();
  if (!l.error.empty()) return state.SkipWithError(l.error.c_str());
  // One thread: OpenCV's own pool (warp, blur) off too; the caller parallelises over
  // images.
  cv::setNumThreads(1);
  // Warm-up, once per process (the pooled scene is the library's): every part's
  // hierarchy built, as after the first few dozen images of a data set. Small images
  // suffice, the hierarchies do not depend on the image size.
  static const bool warm = [&] {
    FullSyntheticSettings small;
    small.width = small.height = 64;
    for (std::int64_t i = 0; i < 64; ++i) {
      render_full_synthetic(small, *l.parts, *l.backgrounds, 1, -1 - i);
    }
    return true;
  }();
  benchmark::DoNotOptimize(warm);
  FullSyntheticSettings settings;
  settings.width = static_cast<int>(state.range(0));
  settings.height = static_cast<int>(state.range(1));
  FullSyntheticStats sum;
  double parts = 0.0;
  std::int64_t index = 0;
  for (auto _ : state) {
    FullSyntheticStats stats;
    const AnnotatedImage image =
        render_full_synthetic(settings, *l.parts, *l.backgrounds, 1, index++, &stats);
    benchmark::DoNotOptimize(image.rgb.data);
    sum.scene_setup_ms += stats.scene_setup_ms;
    sum.sampling_ms += stats.sampling_ms;
    sum.raycast_ms += stats.raycast_ms;
    sum.shading_ms += stats.shading_ms;
    sum.compositing_ms += stats.compositing_ms;
    sum.augmentation_ms += stats.augmentation_ms;
    sum.pose_attempts += stats.pose_attempts;
    parts += double(image.parts.size());
  }
  state.counters["images/s"] =
      benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  const auto per_image = [&](double total) {
    return benchmark::Counter(total, benchmark::Counter::kAvgIterations);
  };
  state.counters["setup_ms"] = per_image(sum.scene_setup_ms);
  state.counters["sample_ms"] = per_image(sum.sampling_ms);
  state.counters["cast_ms"] = per_image(sum.raycast_ms);
  state.counters["shade_ms"] = per_image(sum.shading_ms);
  state.counters["composite_ms"] = per_image(sum.compositing_ms);
  state.counters["augment_ms"] = per_image(sum.augmentation_ms);
  state.counters["parts"] = per_image(parts);
  state.counters["poses"] = per_image(double(sum.pose_attempts));
  state.SetLabel(std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                 ", 1 thread");
}

// Images 0-199 at 300x300, 0-29 at 1280x960: about 5 s and 10 s per repetition (6 s and
// 17 s before the shadow packets).
BENCHMARK(BM_Synth_FullSynthetic)
    ->Args({300, 300})
    ->Iterations(200)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Synth_FullSynthetic)
    ->Args({1280, 960})
    ->Iterations(30)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace flexsight

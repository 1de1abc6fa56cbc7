#pragma once
// One description of the kernel cases, shared by the OpenCL tests (tests/stereo/opencl/, every
// kernel against its reference byte for byte) and the benchmarks (bench/, both paths
// timed): the case tables (sizes, window, step, disparity range, seed), which case
// parameters change each kernel's work, and the inputs every stage starts from, built
// on the host from a textured stereo pair. Tests and benchmarks thus measure what they
// verify. No GoogleTest and no OpenCL here: the reference benchmark includes it too.
#include <algorithm>
#include <cstdint>
#include <opencv2/core.hpp>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "fallback/stereo/image_pyramid.h"
#include "fallback/stereo/patchmatch_reference.h"
#include "fallback/stereo/weight_table.h"
#include "tests/common/random_texture.h"

namespace flexsight::testing_support {

// One case of a level stage.
struct LevelCase {
  int width;
  int height;
  int window;
  int step;
  int ndisp;
  std::uint32_t seed;
  float census_weight = 0.0f;
  float census_cap = 24.0f;  // no cap
};

inline std::string case_name(const LevelCase& c) {
  return std::to_string(c.width) + "x" + std::to_string(c.height) + "_w" +
         std::to_string(c.window) + "s" + std::to_string(c.step) + "_n" +
         std::to_string(c.ndisp) + "_seed" + std::to_string(c.seed) +
         (c.census_weight > 0
              ? "_census" + std::to_string(static_cast<int>(c.census_weight * 100))
              : "") +
         (c.census_cap < 24.0f ? "_cap" + std::to_string(static_cast<int>(c.census_cap)) : "");
}
// GoogleTest prints parameters in test names and messages; bytes would vary by build.
inline void PrintTo(const LevelCase& c, std::ostream* out) { *out << case_name(c); }

// The test table: awkward sizes (1x1, odd widths, and 631x479: a prime width that no
// lane count divides, and many work groups), windows larger than the image,
// steps 1 to 3. Correctness lives in the corners; speed does not, hence a second table.
// The large case keeps a small window and range (and the census term on, capped) so
// that its reference stages stay at seconds.
inline std::vector<LevelCase> level_cases() {
  return {{1, 1, 5, 1, 2, 1},      {7, 5, 5, 2, 4, 2},     {7, 5, 11, 1, 7, 3},
          {33, 17, 11, 2, 16, 4},  {33, 17, 35, 3, 9, 5},  {131, 93, 35, 2, 32, 6},
          {131, 93, 11, 1, 64, 7}, {64, 9, 9, 2, 24, 8},  {7, 5, 5, 2, 4, 9, 0.1f, 10.0f},
          {33, 17, 11, 2, 16, 10, 0.05f}, {131, 93, 35, 2, 32, 11, 0.1f, 6.0f},
          {631, 479, 9, 2, 16, 12, 4.0f, 10.0f}};
}

// ------------------------------------------------------------ the benchmark grid
// Image sizes are 4:3 and named by their width; the window step is the matcher's
// default (StereoParams::window_step), so the timings are those of a real run's coarsest
// level (PPMS's finer levels sample with window_step_fine = 4).
constexpr int kBenchmarkStep = 2;
constexpr int kDefaultNdisp = 64;
constexpr int kDefaultWindow = 35;

inline std::vector<int> benchmark_widths() { return {160, 320, 640}; }
inline std::vector<int> benchmark_ndisps() { return {32, 64}; }
inline std::vector<int> benchmark_windows() { return {21, 35}; }

inline int benchmark_height(int width) { return width * 3 / 4; }

inline LevelCase benchmark_case(int width, int ndisp, int window) {
  return {width, benchmark_height(width), window, kBenchmarkStep, ndisp, 1};
}

// What the benchmarks sweep for one kernel: sizes always, the disparity range and the
// window only where they change the kernel's work (the others stay at the defaults).
// `max_width` keeps the window-cost kernels off the largest size and the whole matcher
// on the smallest: there one run of the reference takes seconds, and the suites (three
// repetitions each) would run for many minutes on two cores.
struct KernelDescription {
  const char* name;  // the OpenClStages method, the reference function, the benchmark
  bool sweeps_ndisp;
  bool sweeps_window;
  int max_width;
};

// Every stage benchmarked on both paths, in pipeline order, with what its benchmark
// sweeps: X(name, sweeps_ndisp, sweeps_window, max_width). The name is the
// OpenClStages method and the reference function ("downsample": the reference's
// colour-and-gradient step; "matcher_*": the whole matcher). Both suites define a
// benchmark function of each name and register this list, so a stage is described
// once. kAll, kCostly, kWhole are the max_width values below.
#define FLEXSIGHT_STEREO_STAGES(X)                                             \
  X(compute_gradient, false, false, kAll)                                      \
  X(downsample, false, false, kAll)                                            \
  /* The random planes' range barely changes the cost work: window only. */    \
  X(init_random_planes, false, true, kCostly)                                  \
  X(evaluate_costs, false, true, kCostly)                                      \
  X(propagate_spatial, false, true, kCostly)                                   \
  X(propagate_view, false, true, kCostly)                                      \
  /* ndisp sets the number of random-search trials. */                         \
  X(refine_random, true, true, kCostly)                                        \
  X(carry_planes_to_finer, false, false, kAll)                                 \
  X(upsample_nearest, false, false, kAll)                                      \
  X(plane_disparities, false, false, kAll)                                     \
  X(lr_confidence, false, false, kAll)                                         \
  X(left_right_check, false, false, kAll)                                      \
  X(fill_inconsistent, false, false, kAll)                                     \
  X(weighted_median_filled, false, true, kAll)                                 \
  /* Its window is the default final_median_window whatever the case. */       \
  X(weighted_median_all, false, false, kAll)                                   \
  X(matcher_ppms, false, false, kWhole)                                        \
  X(matcher_pms, false, false, kWhole)

// The OpenCL path's steps that have no reference function of their own (the reference
// does them inside "downsample", or needs no match records).
#define FLEXSIGHT_STEREO_DEVICE_ONLY_STAGES(X)                                 \
  X(downsample_color, false, false, kAll)                                      \
  X(pack_match_samples, false, false, kAll)

namespace kernel_widths {
constexpr int kAll = 1 << 30;
constexpr int kCostly = 320;
constexpr int kWhole = 160;
}  // namespace kernel_widths

inline std::vector<KernelDescription> kernel_descriptions() {
  using namespace kernel_widths;
#define FLEXSIGHT_DESCRIBE(name, ndisp, window, width) {#name, ndisp, window, width},
  return {FLEXSIGHT_STEREO_DEVICE_ONLY_STAGES(FLEXSIGHT_DESCRIBE)
              FLEXSIGHT_STEREO_STAGES(FLEXSIGHT_DESCRIBE)};
#undef FLEXSIGHT_DESCRIBE
}

inline KernelDescription kernel_description(const std::string& name) {
  for (const KernelDescription& k : kernel_descriptions()) {
    if (name == k.name) return k;
  }
  return {nullptr, false, false, 0};
}

// The (width, ndisp, window) argument lists of a kernel's benchmark (ArgsProduct).
inline std::vector<std::vector<std::int64_t>> benchmark_arguments(const KernelDescription& k) {
  std::vector<std::int64_t> widths;
  for (int w : benchmark_widths()) {
    if (w <= k.max_width) widths.push_back(w);
  }
  auto sweep = [](bool swept, const std::vector<int>& values, int fixed) {
    return swept ? std::vector<std::int64_t>(values.begin(), values.end())
                 : std::vector<std::int64_t>{fixed};
  };
  return {widths, sweep(k.sweeps_ndisp, benchmark_ndisps(), kDefaultNdisp),
          sweep(k.sweeps_window, benchmark_windows(), kDefaultWindow)};
}

// ------------------------------------------------------- the inputs of the stages

// A textured RGB8 stereo pair of `c`'s size: the right view is the left one shifted by
// a few pixels, so that costs vary as on real images.
struct TexturedPair {
  cv::Mat left;
  cv::Mat right;
};

inline TexturedPair textured_pair(const LevelCase& c) {
  const int shift = std::min(3, c.ndisp - 1);
  cv::Mat wide = random_rgb8(c.width + shift, c.height, c.seed);
  return {wide(cv::Rect(shift, 0, c.width, c.height)).clone(),
          wide(cv::Rect(0, 0, c.width, c.height)).clone()};
}

// textured_pair's views, the weight table and the reference's random initial planes of
// both views: the common starting point of the stage tests and benchmarks. `threads`
// only changes how fast the planes' costs are computed.
struct ReferenceLevel {
  ViewImage images[2];
  // A short distance bandwidth, so that every stage test sees the distance factors.
  std::vector<float> weights = make_support_weight_table(10.0f, 12.0f);
  LevelInputs in;
  PlaneField fields[2];

  explicit ReferenceLevel(const LevelCase& c, int threads = 2) {
    const TexturedPair pair = textured_pair(c);
    images[PMS_VIEW_LEFT] = make_view_image(pair.left);
    images[PMS_VIEW_RIGHT] = make_view_image(pair.right);
    for (int view = 0; view < 2; ++view) in.views[view] = &images[view];
    in.weights = weights.data();
    in.cost = {c.window / 2, c.window / 2, c.step, 0.9f, 1.0f - 0.9f, 10.0f, 2.0f,
               c.census_weight, c.census_cap};
    in.ndisp = c.ndisp;
    in.seed = c.seed;
    in.threads = threads;
    for (int view = 0; view < 2; ++view) init_random_planes(in, view, 0, fields[view]);
  }
};

// The search of the coarsest level for the level's disparity range, with the confidence
// rules of the finer levels (which apply only where a confidence map is passed).
inline SearchSchedule search_schedule(int ndisp) {
  SearchSchedule schedule;
  schedule.initial_range = 0.5f * static_cast<float>(ndisp);
  schedule.normal_range = 1.0f;
  schedule.min_range = 0.25f;
  schedule.confident_threshold = 0.5f;
  schedule.confident_max_range = 2.0f;
  schedule.confident_spatial_candidates = 8;
  return schedule;
}

// The two fields after a first spatial step, so that propagation and refinement start
// from planes that differ between neighbours and views.
inline void advance(ReferenceLevel& f) {
  const SearchSchedule schedule = search_schedule(f.in.ndisp);
  for (int view = 0; view < 2; ++view) {
    propagate_spatial(f.in, view, 0, schedule, nullptr, f.fields[view]);
  }
}

// A random confidence in [0, 1) per pixel: about half the pixels count as confident at
// search_schedule's threshold.
inline std::vector<float> random_confidence(int pixels, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> confidence(pixels);
  for (float& c : confidence) c = u(rng);
  return confidence;
}

// Disparities of both views where about a third of the left pixels agree exactly with
// the right pixel they point at, a third nearly (within or just past the tolerance) and
// a third not at all; some point outside the image.
struct DisparityPair {
  std::vector<float> left;
  std::vector<float> right;
};

inline DisparityPair random_disparities(int width, int height, int ndisp, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(0.0f, static_cast<float>(ndisp - 1));
  std::uniform_int_distribution<int> kind(0, 2);
  std::uniform_real_distribution<float> offset(-1.5f, 1.5f);
  DisparityPair pair;
  pair.right.resize(static_cast<size_t>(width) * height);
  for (float& v : pair.right) v = d(rng);
  pair.left.resize(pair.right.size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      float value = d(rng);
      float match = pms_floor_round(static_cast<float>(x) - value);
      int k = kind(rng);
      if (k < 2 && match >= 0.0f && match <= static_cast<float>(width - 1)) {
        float other = pair.right[y * width + static_cast<int>(match)];
        value = k == 0 ? other : std::max(0.0f, other + offset(rng));
      }
      pair.left[y * width + x] = value;
    }
  }
  return pair;
}

// Consistency flags where a row is all consistent, all inconsistent or mixed.
inline std::vector<std::uint8_t> random_consistency(int width, int height, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> row_kind(0, 4);
  std::bernoulli_distribution bit(0.6);
  std::vector<std::uint8_t> consistent(static_cast<size_t>(width) * height);
  for (int y = 0; y < height; ++y) {
    int kind = row_kind(rng);
    for (int x = 0; x < width; ++x) {
      consistent[y * width + x] =
          kind == 0 ? 0 : kind == 1 ? 1 : static_cast<std::uint8_t>(bit(rng));
    }
  }
  return consistent;
}

// The weighted median's inputs: the left view's plane disparities, consistency flags
// and the median's own weight table (a bandwidth other than the cost's).
struct MedianInputs {
  std::vector<float> disparity;
  std::vector<std::uint8_t> consistent;
  std::vector<float> weights;
  int radius;
  int step;
  float background_margin;  // StereoParams::median_background_margin
};

inline MedianInputs median_inputs(const ReferenceLevel& f, const LevelCase& c) {
  return {plane_disparities(f.fields[PMS_VIEW_LEFT], 2),
          random_consistency(c.width, c.height, c.seed + 1), make_support_weight_table(7.5f),
          c.window / 2, c.step, 2.0f};
}

}  // namespace flexsight::testing_support

#pragma once
// How much work one call of each stage does, for the benchmarks' counters (pixels/s,
// evals/s, GFLOP/s, GB/s). Both suites (bench_opencl.cpp, bench_reference.cpp) use it,
// so their rates are comparable and their ratio is the ratio of their times.
//
// The matching cost. Nearly all the time of the PatchMatch stages is pms_plane_cost
// (kernels/stereo/pms_math.h; the OpenCL lanes of pms_lane_cost.h do the same operations
// per lane). One window sample, i.e. one pass of its inner loop, costs:
//   flops (add, sub, mul, abs, min, max, floor: 1 each; int/float conversions free)
//      3  d = a*qx + row_term + c
//      4  match_x = fmin(fmax(qx + direction*d, 0), max_x)
//      2  x0f = floor(match_x), t = match_x - x0f
//     17  colour: 3 channels x (m1-m0, t*, m0+, q-, fabs) + 2 adds
//     11  gradient: 2 channels x 5 + 1 add
//      5  dissimilarity: 2 fmin, 2 mul, 1 add
//      4  census: nearest pixel (1 compare), xor, popcount, mul and add to the rest
//      8  weight index pms_color_l1(centre, q): 3 sub, 3 fabs, 2 add
//      1  w = colour weight * distance weight
//      2  sum = sum + w * dissimilarity
//     57  in all (row_term, 1 mul per window row, is left out)
//   bytes the loads request (what the load units move, mostly from cache: the
//   working set of a row of windows fits in L2, so this is not DRAM traffic)
//     12  q: colour r, g, b of the window pixel
//     24  m0, m1: the other view's colour at x0 and x1
//      8  g: gradient of the window pixel
//     16  g0, g1: the other view's gradient at x0 and x1
//      8  the support weight's colour and distance factors
//      8  the census of the window pixel and of the nearest matched pixel
//     76  in all
//   (the OpenCL lanes read the other view's part, 44 of these bytes, as one 64-byte
//   load of a match record, kernels/stereo/pms_lane_cost.h; the rates use the 76.)
// Samples per window: offsets k*step in [-radius, radius] (the grid goes through 0),
// so 2*(radius/step) + 1 per side, (2*(radius/step) + 1)^2 for an inner pixel (289 at
// window 35 step 2, 121 at window 21), fewer near the border where window pixels
// outside the image are left out; window_samples() counts them exactly.
//
// Rules of the count:
//  - A candidate evaluation ("eval") is one pms_plane_cost call; the stages' nominal
//    candidates are counted: propagate_spatial the in-image neighbours of
//    pms_spatial_offset, propagate_view 1, refine_random pms_search_trial_count trials.
//    Candidates the stage skips (duplicate planes, matches outside the image, steep
//    perturbations) are counted too.
//  - Every evaluation counts its full window. propagate_* and refine_random stop a sum
//    once it reaches the best cost so far (the early exit), so for them GFLOP/s and
//    GB/s are window-equivalent rates, an upper bound of the arithmetic really done;
//    init_random_planes and evaluate_costs have no bound, so theirs are exact.
//  - The per-pixel bookkeeping outside the window (random numbers, plane maths, loading
//    and storing the best plane) is under 1% of the window work and left out of the
//    flops; the bytes of loading and storing planes and costs are counted.
//  - The stages without a window count their pixel's loads, stores and arithmetic as
//    written in kernels/*.cl (see each PixelCost below).
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "host/stereo/stereo_params.h"
#include "host/stereo/pipeline_rules.h"
#include "kernels/stereo/pms_math.h"

namespace flexsight::bench {

constexpr double kCostFlopsPerSample = 57;
constexpr double kCostBytesPerSample = 76;

// What one call of a stage processes.
struct Work {
  double pixels = 0;       // pixels the stage is about (its output, or its input level)
  double evaluations = 0;  // plane-candidate cost evaluations (0: not a cost stage)
  double flops = 0;
  double bytes = 0;

  Work& operator+=(const Work& other) {
    pixels += other.pixels;
    evaluations += other.evaluations;
    flops += other.flops;
    bytes += other.bytes;
    return *this;
  }
};

// Window offsets of one axis that pms_plane_cost sums at coordinate `p` of `size`.
inline int window_offsets(int size, int radius, int step, int p) {
  const int begin = pms_first_offset(radius, step, -p);
  const int end = radius < size - 1 - p ? radius : size - 1 - p;
  return end < begin ? 0 : (end - begin) / step + 1;
}

// A cost stage on a width x height level: `candidates(x, y)` evaluations at pixel (x, y),
// each over that pixel's window, plus `bytes_per_pixel` of plane and cost traffic and
// `bytes_per_candidate` of candidate planes read.
template <typename Candidates>
Work cost_stage_work(int width, int height, const PmsCostParams& cost,
                     const Candidates& candidates, double bytes_per_pixel,
                     double bytes_per_candidate = 0) {
  std::vector<int> columns(width);
  for (int x = 0; x < width; ++x) columns[x] = window_offsets(width, cost.radius, cost.step, x);
  Work work;
  double samples = 0;
  for (int y = 0; y < height; ++y) {
    const int rows = window_offsets(height, cost.radius, cost.step, y);
    for (int x = 0; x < width; ++x) {
      const int n = candidates(x, y);
      work.evaluations += n;
      samples += static_cast<double>(n) * rows * columns[x];
    }
  }
  work.pixels = static_cast<double>(width) * height;
  work.flops = samples * kCostFlopsPerSample;
  work.bytes = samples * kCostBytesPerSample + work.pixels * bytes_per_pixel +
               work.evaluations * bytes_per_candidate;
  return work;
}

// init_random_planes: one unbounded cost per pixel; writes 4 plane floats and the cost.
inline Work init_random_planes_work(int width, int height, const PmsCostParams& cost) {
  return cost_stage_work(width, height, cost, [](int, int) { return 1; }, 20);
}

// evaluate_costs: one unbounded cost per pixel; reads a plane (12 B), writes the cost.
inline Work evaluate_costs_work(int width, int height, const PmsCostParams& cost) {
  return cost_stage_work(width, height, cost, [](int, int) { return 1; }, 16);
}

// The best plane of a pixel loaded (plane 12 B + cost 4 B) and stored (16 B): the
// traffic of every candidate stage besides its windows.
constexpr double kBestPlaneBytes = 32;

// propagate_spatial over both parities (every pixel once): the in-image neighbours of
// pms_spatial_offset, each plane read (12 B).
inline Work propagate_spatial_work(int width, int height, const PmsCostParams& cost) {
  auto neighbours = [&](int x, int y) {
    int n = 0;
    for (int candidate = 0; candidate < PMS_SPATIAL_CANDIDATES; ++candidate) {
      int dx = 0;
      int dy = 0;
      pms_spatial_offset(candidate, &dx, &dy);
      n += x + dx >= 0 && x + dx < width && y + dy >= 0 && y + dy < height;
    }
    return n;
  };
  return cost_stage_work(width, height, cost, neighbours, kBestPlaneBytes, 12);
}

// propagate_view over both parities: one candidate per pixel, the other view's plane.
inline Work propagate_view_work(int width, int height, const PmsCostParams& cost) {
  return cost_stage_work(width, height, cost, [](int, int) { return 1; }, kBestPlaneBytes, 12);
}

// refine_random over both parities, without confidence: every trial of the schedule.
inline Work refine_random_work(int width, int height, const PmsCostParams& cost,
                               const SearchSchedule& schedule) {
  const int trials = pms_search_trial_count(schedule.initial_range, schedule.min_range);
  return cost_stage_work(width, height, cost, [&](int, int) { return trials; }, kBestPlaneBytes);
}

// What a stage without a window does per pixel, as written in kernels/*.cl.
struct PixelCost {
  double flops;
  double bytes;  // loaded and stored
};

// downsample_color, per coarse pixel: 3 channels x (3 adds, + 2, * 0.25, floor) = 18
// flops; loads 4 pixels x 3 floats (48 B), stores 4 floats.
constexpr PixelCost kDownsampleColorCost{18, 64};
// compute_gradient, per pixel: 4 grey values (2 adds each), 2 differences, 2 scalings
// = 12 flops; loads 4 neighbours x 3 floats (48 B), stores 2 floats.
constexpr PixelCost kComputeGradientCost{12, 56};
// pack_match_samples (OpenCL only), per pixel: 5 differences; loads the colour and
// gradient at x and x + 1 (48 B), stores a 48-byte record.
constexpr PixelCost kPackMatchSamplesCost{5, 96};
// carry_planes_to_finer, per fine pixel: 4 flops (2c, a+b, *0.5, -); loads 12 B,
// stores 16 B.
constexpr PixelCost kCarryPlanesToFinerCost{4, 28};
// upsample_nearest, per fine pixel: a copy (4 B in, 4 B out).
constexpr PixelCost kUpsampleNearestCost{0, 8};
// plane_disparities, per pixel: a*x + b*y + c = 4 flops; loads 12 B, stores 4 B.
constexpr PixelCost kPlaneDisparitiesCost{4, 16};
// lr_confidence, per pixel: the match x + direction*d rounded (4), |d - d'| (2),
// 1 / (1 + .) (2) = 8 flops; loads 2 disparities, stores 1 float.
constexpr PixelCost kLrConfidenceCost{8, 12};
// left_right_check, per pixel: the match (4) and |d - d'| (2) = 6 flops; loads 2
// disparities (8 B), stores 1 byte.
constexpr PixelCost kLeftRightCheckCost{6, 9};

// A stage without a window over `pixels`, `cost` per pixel.
inline Work pixel_stage_work(double pixels, PixelCost cost) {
  Work work;
  work.pixels = pixels;
  work.flops = pixels * cost.flops;
  work.bytes = pixels * cost.bytes;
  return work;
}

// A stage without a window over every pixel of a width x height level (the finer level
// for carry_planes_to_finer and upsample_nearest).
inline Work pixel_stage_work(int width, int height, PixelCost cost) {
  return pixel_stage_work(static_cast<double>(width) * height, cost);
}

inline double coarse_pixels(int width, int height) {
  return static_cast<double>((width + 1) / 2) * ((height + 1) / 2);
}

// downsample_color of a width x height level, per coarse pixel. `pixels` is the fine
// level's: the benchmark is named by the level it reads.
inline Work downsample_color_work(int width, int height) {
  Work work = pixel_stage_work(coarse_pixels(width, height), kDownsampleColorCost);
  work.pixels = static_cast<double>(width) * height;
  return work;
}

// The reference's downsample: the coarse colour, then the coarse gradient.
inline Work downsample_work(int width, int height) {
  Work work = downsample_color_work(width, height);
  Work gradient = pixel_stage_work((width + 1) / 2, (height + 1) / 2, kComputeGradientCost);
  work.flops += gradient.flops;
  work.bytes += gradient.bytes;
  return work;
}

// fill_inconsistent: every pixel loads its flag and stores 16 B; a consistent pixel
// loads its plane (16 B); an inconsistent one scans the flags to the nearest consistent
// pixel on each side (1 B each, counted exactly from `consistent`) and compares the
// two planes' disparities there (8 flops, 2 x 12 B).
inline Work fill_inconsistent_work(int width, int height,
                                   const std::vector<std::uint8_t>& consistent) {
  Work work;
  work.pixels = static_cast<double>(width) * height;
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* row = &consistent[static_cast<size_t>(y) * width];
    for (int x = 0; x < width; ++x) {
      work.bytes += 1 + 16;
      if (row[x]) {
        work.bytes += 16;
        continue;
      }
      int left = x - 1;
      while (left >= 0 && !row[left]) --left;
      int right = x + 1;
      while (right < width && !row[right]) ++right;
      work.bytes += (x - left) + (right - x) + 4 /* fourth component */;
      if (left >= 0 && right < width) {
        work.flops += 8;
        work.bytes += 24;
      } else {
        work.bytes += 12;
      }
    }
  }
  return work;
}

// weighted_median_filled: a consistent pixel copies its disparity (4 B + 1 B flag in,
// 4 B out). An inconsistent one gathers its n window samples (disparity 4 B, colour
// 12 B, weight 4 B each; 8 flops of pms_color_l1 each), then pms_weighted_median sums
// the n weights once and once per binary-search step (ceil(log2 n) steps): n (1 + steps)
// adds. The insertion sort's comparisons (O(n^2)) are not arithmetic and are left out,
// so this kernel's GFLOP/s stays low whatever its speed.
// A weighted median over the pixels where `consistent` is 0 (every pixel when it is
// null): per sample `bytes_per_sample` of loads, 8 flops of weight index and the
// binary search's passes; a skipped pixel copies its disparity.
inline Work weighted_median_work(int width, int height, const std::uint8_t* consistent,
                                 int radius, int step, double bytes_per_sample) {
  std::vector<int> columns(width);
  for (int x = 0; x < width; ++x) columns[x] = window_offsets(width, radius, step, x);
  Work work;
  work.pixels = static_cast<double>(width) * height;
  for (int y = 0; y < height; ++y) {
    const int rows = window_offsets(height, radius, step, y);
    for (int x = 0; x < width; ++x) {
      work.bytes += 1 + 4;
      if (consistent && consistent[static_cast<size_t>(y) * width + x]) {
        work.bytes += 4;
        continue;
      }
      const double n = static_cast<double>(rows) * columns[x];
      const double steps = n > 1 ? std::ceil(std::log2(n)) : 0;
      work.bytes += bytes_per_sample * n;
      work.flops += 8 * n + n * (1 + steps);
    }
  }
  return work;
}

// weighted_median_filled: the consistency flag, colour and disparity of each sample.
inline Work weighted_median_filled_work(int width, int height,
                                        const std::vector<std::uint8_t>& consistent,
                                        int radius, int step) {
  return weighted_median_work(width, height, consistent.data(), radius, step, 21);
}

// weighted_median_all: every pixel, step 1, colour and disparity of each sample.
inline Work weighted_median_all_work(int width, int height, int radius) {
  return weighted_median_work(width, height, nullptr, radius, 1, 20);
}

// The PatchMatch stages of a whole run of the matcher (run_stereo's stage list with
// nominal candidates; refine_random counts every trial, as without confidence). The
// post-processing, whose work depends on how many pixels fail the left/right check, is
// left out: it is a few percent of a run. `pixels` is the input's.
inline Work matcher_work(const StereoParams& params, int width, int height) {
  const int levels = pipeline_level_count(params, width, height);
  std::vector<std::pair<int, int>> sizes{{width, height}};
  for (int level = 1; level < levels; ++level) {
    sizes.push_back({(sizes.back().first + 1) / 2, (sizes.back().second + 1) / 2});
  }
  Work work;
  for (int level = levels - 1; level >= 0; --level) {
    const auto [w, h] = sizes[level];
    const LevelPlan plan = plan_level(params, level, levels, w, h);
    for (int view = 0; view < 2; ++view) {
      work += plan.coarsest ? init_random_planes_work(w, h, plan.cost)
                            : evaluate_costs_work(w, h, plan.cost);
      for (int iteration = 0; iteration < plan.iterations; ++iteration) {
        work += propagate_spatial_work(w, h, plan.cost);
        work += propagate_view_work(w, h, plan.cost);
        work += refine_random_work(w, h, plan.cost, plan.schedule);
      }
    }
  }
  work.pixels = static_cast<double>(width) * height;
  return work;
}

}  // namespace flexsight::bench

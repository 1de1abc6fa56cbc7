#include "fallback/stereo/postprocess_reference.h"

#include <algorithm>
#include <cfloat>

#include "kernels/stereo/postprocess_math.h"

namespace flexsight {

std::vector<std::uint8_t> left_right_check(const std::vector<float>& disparity,
                                           const std::vector<float>& other_disparity, int width,
                                           int height, int view, float tolerance, int threads) {
  const float direction = view == PMS_VIEW_LEFT ? -1.0f : 1.0f;
  std::vector<std::uint8_t> consistent(disparity.size());
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      consistent[y * width + x] = static_cast<std::uint8_t>(pms_lr_consistent(
          disparity.data(), other_disparity.data(), width, x, y, direction, tolerance));
    }
  }
  return consistent;
}

std::vector<float> fill_inconsistent(const std::vector<float>& planes,
                                     const std::vector<std::uint8_t>& consistent, int width,
                                     int height, float max_extrapolation, int threads) {
  std::vector<float> filled(planes);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      int index = y * width + x;
      if (consistent[index]) continue;
      pms_fill_pixel(planes.data(), consistent.data(), width, x, y, max_extrapolation,
                     &filled[4 * index]);
    }
  }
  return filled;
}

namespace {

// The weighted median at every pixel where `filter` is nonzero (every pixel when it is
// null), voting the window pixels where `usable` is nonzero (all when null) whose
// disparity is at most the pixel's own plus `margin`.
std::vector<float> weighted_median(const std::vector<float>& disparity,
                                   const std::uint8_t* filter, const std::uint8_t* usable,
                                   float margin, const ViewImage& image, const float* weights,
                                   int radius, int step, int threads) {
  const int width = image.width;
  const int height = image.height;
  std::vector<float> filtered(disparity);
  const int side = 2 * (radius / step) + 1;  // samples per window row
#pragma omp parallel num_threads(threads)
  {
    std::vector<float> values(static_cast<size_t>(side) * side);
    std::vector<float> sample_weights(values.size());
    std::vector<float> sorted(values.size());
#pragma omp for schedule(dynamic, 2)
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        int index = y * width + x;
        if (filter && !filter[index]) continue;
        int n = pms_gather_median_samples(disparity.data(), usable, disparity[index] + margin,
                                          image.color.data(), weights, width, height, x, y,
                                          radius, step, values.data(), sample_weights.data());
        if (n == 0) continue;
        std::copy(values.begin(), values.begin() + n, sorted.begin());
        std::sort(sorted.begin(), sorted.begin() + n);
        filtered[index] = pms_weighted_median(values.data(), sample_weights.data(), sorted.data(), n);
      }
    }
  }
  return filtered;
}

}  // namespace

std::vector<float> weighted_median_filled(const std::vector<float>& disparity,
                                          const std::vector<std::uint8_t>& consistent,
                                          const ViewImage& image, const float* weights,
                                          int radius, int step, float background_margin,
                                          int threads) {
  std::vector<std::uint8_t> inconsistent(consistent.size());
  for (size_t i = 0; i < consistent.size(); ++i) inconsistent[i] = !consistent[i];
  return weighted_median(disparity, inconsistent.data(), consistent.data(), background_margin,
                         image, weights, radius, step, threads);
}

std::vector<float> weighted_median_all(const std::vector<float>& disparity,
                                       const ViewImage& image, const float* weights, int radius,
                                       int threads) {
  // FLT_MAX: every disparity votes (d + FLT_MAX rounds to FLT_MAX, as in the kernel).
  return weighted_median(disparity, nullptr, nullptr, FLT_MAX, image, weights, radius, 1,
                         threads);
}

std::vector<std::uint8_t> large_segment_mask(const std::vector<float>& disparity, int width,
                                             int height, float max_step, int min_size,
                                             bool follow_slopes) {
  // Breadth-first search of each segment once; the kernels find the same segments by
  // label propagation (small_segments.cl), and the mask does not depend on the method.
  std::vector<std::uint8_t> large(disparity.size(), 1);
  if (min_size <= 0) return large;
  std::vector<std::uint8_t> seen(disparity.size(), 0);
  std::vector<int> segment;
  for (int start = 0; start < width * height; ++start) {
    if (seen[start]) continue;
    segment.assign(1, start);
    seen[start] = 1;
    for (size_t next = 0; next < segment.size(); ++next) {
      const int p = segment[next];
      const int x = p % width;
      const int y = p / width;
      const int neighbours[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
      for (const auto& n : neighbours) {
        if (n[0] < 0 || n[0] >= width || n[1] < 0 || n[1] >= height) continue;
        const int q = n[1] * width + n[0];
        if (seen[q]) continue;
        // The pair is named by its first pixel (left or upper), as the kernel names it.
        const bool horizontal = n[1] == y;
        const int first_x = std::min(x, n[0]);
        const int first_y = std::min(y, n[1]);
        if (!pms_segment_pair_joined(disparity.data(), width, height, first_x, first_y,
                                     horizontal, max_step, follow_slopes)) {
          continue;
        }
        seen[q] = 1;
        segment.push_back(q);
      }
    }
    if (static_cast<int>(segment.size()) < min_size) {
      for (int p : segment) large[p] = 0;
    }
  }
  return large;
}

void mask_and(std::vector<std::uint8_t>& mask, const std::vector<std::uint8_t>& other) {
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = mask[i] && other[i] ? 1 : 0;
}

std::vector<float> flat_planes(const std::vector<float>& disparity) {
  std::vector<float> planes(4 * disparity.size());
  for (size_t i = 0; i < disparity.size(); ++i) pms_flat_plane(disparity[i], &planes[4 * i]);
  return planes;
}

}  // namespace flexsight

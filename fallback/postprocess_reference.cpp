#include "fallback/postprocess_reference.h"

#include <algorithm>
#include <cfloat>

#include "kernels/postprocess_math.h"

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

}  // namespace flexsight

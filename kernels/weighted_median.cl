/* The two weighted medians of the post-processing (postprocess_math.h): over the
 * inconsistent pixels with the consistent ones voting (reference: weighted_median_filled),
 * and over every pixel (reference: weighted_median_all). */
#include "postprocess_math.h"
#include "pms_kernel_support.h"

/* Private sample arrays: the host passes (2 (radius / step) + 1)^2 for the run's window,
 * so that a small window does not pay for the largest one. */
#ifndef PMS_MEDIAN_MAX_SAMPLES
#define PMS_MEDIAN_MAX_SAMPLES 289 /* window 35, step 2 */
#endif

/* Ascending order. The reference uses std::sort, and pms_weighted_median only needs the
 * same values in ascending order (see postprocess_math.h), so any sort gives its bytes. */
inline void pms_insertion_sort(float* values, int n) {
  for (int i = 1; i < n; ++i) {
    float v = values[i];
    int j = i - 1;
    while (j >= 0 && values[j] > v) {
      values[j + 1] = values[j];
      --j;
    }
    values[j + 1] = v;
  }
}

/* The weighted median at (x, y) of the window pixels where `usable` is nonzero (all when
 * it is 0) and the disparity is at most `max_value`, or the pixel's own disparity when
 * none is. */
inline float pms_median_at(const __global float* disparity, const __global uchar* usable,
                           float max_value, const __global float* color,
                           const __global float* weights, int width, int height, int x, int y,
                           int radius, int step) {
  float values[PMS_MEDIAN_MAX_SAMPLES];
  float sample_weights[PMS_MEDIAN_MAX_SAMPLES];
  float sorted[PMS_MEDIAN_MAX_SAMPLES];
  int n = pms_gather_median_samples(disparity, usable, max_value, color, weights, width, height,
                                    x, y, radius, step, values, sample_weights);
  if (n == 0) return disparity[y * width + x];
  for (int i = 0; i < n; ++i) sorted[i] = values[i];
  pms_insertion_sort(sorted, n);
  return pms_weighted_median(values, sample_weights, sorted, n);
}

__kernel void weighted_median_filled(const __global float* disparity,
                                     const __global uchar* consistent,
                                     const __global float* color, const __global float* weights,
                                     int width, int height, int radius, int step,
                                     float background_margin, __global float* filtered) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  int index = y * width + x;
  filtered[index] =
      consistent[index]
          ? disparity[index]
          : pms_median_at(disparity, consistent, disparity[index] + background_margin, color,
                          weights, width, height, x, y, radius, step);
}

/* Every pixel, every window pixel voting, step 1 (reference: weighted_median_all). */
__kernel void weighted_median_all(const __global float* disparity, const __global float* color,
                                  const __global float* weights, int width, int height,
                                  int radius, __global float* filtered) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  filtered[y * width + x] =
      pms_median_at(disparity, 0, FLT_MAX, color, weights, width, height, x, y, radius, 1);
}

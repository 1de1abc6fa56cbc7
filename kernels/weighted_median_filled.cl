/* Weighted median of the window's disparities for every inconsistent pixel; consistent
 * pixels copy theirs (reference: weighted_median_filled). */
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

__kernel void weighted_median_filled(const __global float* disparity,
                                     const __global uchar* consistent,
                                     const __global float* color, const __global float* weights,
                                     int width, int height, int radius, int step,
                                     __global float* filtered) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  int index = y * width + x;
  if (consistent[index]) {
    filtered[index] = disparity[index];
    return;
  }
  float values[PMS_MEDIAN_MAX_SAMPLES];
  float sample_weights[PMS_MEDIAN_MAX_SAMPLES];
  float sorted[PMS_MEDIAN_MAX_SAMPLES];
  int n = pms_gather_median_samples(disparity, color, weights, width, height, x, y, radius,
                                    step, values, sample_weights);
  for (int i = 0; i < n; ++i) sorted[i] = values[i];
  pms_insertion_sort(sorted, n);
  filtered[index] = pms_weighted_median(values, sample_weights, sorted, n);
}

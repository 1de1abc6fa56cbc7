/* The two weighted medians of the post-processing (postprocess_math.h): over the
 * inconsistent pixels with the consistent ones voting (reference: weighted_median_filled),
 * and over every pixel (reference: weighted_median_all). */
#include "postprocess_math.h"
#include "pms_lanes.h"

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
#if PMS_LANES > 1
/* PMS_LANES pixels of a row per work item (pms_dense_lanes), one per vector lane. PoCL
 * runs the per-pixel version below lane by lane, and its insertion sort branches on
 * every comparison. Here no sort: for each sample value v, the weight of the samples
 * <= v, summed in sample order exactly as pms_weighted_median sums it (a sample left out
 * adds 0.0f, which changes no bit of a sum of positive weights), and the smallest v
 * whose sum reaches half the total, which is the value pms_weighted_median's binary
 * search finds since that sum only grows with v. Samples outside the image are left
 * out per lane, as the reference leaves them out of its list. */
__kernel void weighted_median_all(const __global float* disparity, const __global float* color,
                                  const __global float* weights, int width, int height,
                                  int radius, __global float* filtered) {
  PmsLanes lanes;
  int y;
  if (!pms_dense_lanes(width, height, &lanes, &y)) return;
  const pms_intv px = PMS_VLOAD(0, lanes.x);
  float centre[3][PMS_LANES];
  for (int l = 0; l < PMS_LANES; ++l) {
    for (int ch = 0; ch < 3; ++ch) centre[ch][l] = color[4 * (y * width + lanes.x[l]) + ch];
  }
  const pms_floatv cr = PMS_VLOAD(0, centre[0]);
  const pms_floatv cg = PMS_VLOAD(0, centre[1]);
  const pms_floatv cb = PMS_VLOAD(0, centre[2]);
  pms_floatv values[PMS_MEDIAN_MAX_SAMPLES];
  pms_floatv votes[PMS_MEDIAN_MAX_SAMPLES]; /* the support weight, 0 outside the image */
  pms_intv inside[PMS_MEDIAN_MAX_SAMPLES];
  int n = 0;
  for (int dy = -radius; dy <= radius; ++dy) {
    const int qy = y + dy;
    const int row_inside = qy >= 0 && qy < height;
    const int row = (qy < 0 ? 0 : (qy > height - 1 ? height - 1 : qy)) * width;
    for (int dx = -radius; dx <= radius; ++dx, ++n) {
      float v[PMS_LANES], r[PMS_LANES], g[PMS_LANES], b[PMS_LANES];
      for (int l = 0; l < PMS_LANES; ++l) {
        int qx = lanes.x[l] + dx;
        qx = qx < 0 ? 0 : (qx > width - 1 ? width - 1 : qx);
        v[l] = disparity[row + qx];
        r[l] = color[4 * (row + qx)];
        g[l] = color[4 * (row + qx) + 1];
        b[l] = color[4 * (row + qx) + 2];
      }
      const pms_intv qx = px + dx;
      inside[n] = (qx >= 0) & (qx < width) & (pms_intv)(row_inside ? -1 : 0);
      values[n] = PMS_VLOAD(0, v);
      /* pms_color_l1(centre, q), lane by lane */
      const pms_intv index = PMS_TO_INTV(fabs(cr - PMS_VLOAD(0, r)) + fabs(cg - PMS_VLOAD(0, g)) +
                                         fabs(cb - PMS_VLOAD(0, b)));
      float w[PMS_LANES];
      for (int l = 0; l < PMS_LANES; ++l) w[l] = weights[PMS_LANE(index, l)];
      votes[n] = select((pms_floatv)(0.0f), PMS_VLOAD(0, w), inside[n]);
    }
  }
  pms_floatv total = (pms_floatv)(0.0f);
  for (int i = 0; i < n; ++i) total = total + votes[i];
  const pms_floatv half_total = total * 0.5f;
  pms_floatv median = (pms_floatv)(0.0f);
  pms_intv found = (pms_intv)(0);
  for (int i = 0; i < n; ++i) {
    const pms_floatv v = values[i];
    pms_floatv below = (pms_floatv)(0.0f);
    for (int j = 0; j < n; ++j) {
      below = below + select((pms_floatv)(0.0f), votes[j], inside[j] & (values[j] <= v));
    }
    const pms_intv better =
        inside[i] & (below >= half_total) & ((found == (pms_intv)(0)) | (v < median));
    median = select(median, v, better);
    found = found | better;
  }
  for (int l = 0; l < PMS_LANES; ++l) {
    if (lanes.active[l]) filtered[y * width + lanes.x[l]] = PMS_LANE(median, l);
  }
}
#else
__kernel void weighted_median_all(const __global float* disparity, const __global float* color,
                                  const __global float* weights, int width, int height,
                                  int radius, __global float* filtered) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  filtered[y * width + x] =
      pms_median_at(disparity, 0, FLT_MAX, color, weights, width, height, x, y, radius, 1);
}
#endif

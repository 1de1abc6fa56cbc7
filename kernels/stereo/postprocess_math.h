/*
 * Per-pixel mathematics of the stages around PatchMatch: left/right confidence and
 * consistency, filling of inconsistent pixels, and the weighted median. Shared by the
 * reference path (C++) and the kernels (OpenCL C); same rules as pms_math.h.
 *
 * The weighted median runs twice. First on the pixels that failed the left/right check,
 * voting only the pixels that passed and lie at most a margin in front of the filled
 * background (the hole filling). Then, with a small window, on
 * every pixel: PatchMatch leaves isolated wrong planes (one unlucky random candidate
 * that won), which a 7x7 median removes: it takes about a point off bad-2 (all)
 * (docs/tuning-log.md).
 */
#ifndef FLEXSIGHT_POSTPROCESS_MATH_H
#define FLEXSIGHT_POSTPROCESS_MATH_H

#include "pms_math.h"

/* Disparity of the other view at the pixel that (x, y) with disparity d matches, or -1
 * when that pixel lies outside the image. direction: -1 left view, +1 right view. */
FS_INLINE float pms_matched_disparity(const FS_GLOBAL float* other_disparity, int width,
                                       int x, int y, float d, float direction) {
  float match_x = pms_floor_round((float)x + direction * d);
  if (match_x < 0.0f || match_x > (float)(width - 1)) return -1.0f;
  return other_disparity[y * width + (int)match_x];
}

/* The paper's confidence C(p) = 1 / (1 + |d_p - d_p'|); 0 where p' is outside. */
FS_INLINE float pms_confidence(const FS_GLOBAL float* disparity,
                                const FS_GLOBAL float* other_disparity, int width, int x, int y,
                                float direction) {
  float d = disparity[y * width + x];
  float d_other = pms_matched_disparity(other_disparity, width, x, y, d, direction);
  if (d_other < 0.0f) return 0.0f;
  return 1.0f / (1.0f + FS_FABS(d - d_other));
}

/* Left/right check: 1 when both views agree within `tolerance` pixels. */
FS_INLINE int pms_lr_consistent(const FS_GLOBAL float* disparity,
                                 const FS_GLOBAL float* other_disparity, int width, int x,
                                 int y, float direction, float tolerance) {
  float d = disparity[y * width + x];
  float d_other = pms_matched_disparity(other_disparity, width, x, y, d, direction);
  return d_other >= 0.0f && FS_FABS(d - d_other) <= tolerance;
}

/* The disparity that the plane of consistent pixel `source_x` (on row y) gives at
 * (x, y), kept within max_extrapolation of the source's own disparity: a plane fitted
 * to a window is right near it, but its slope, carried tens of pixels across a hole,
 * lands far from the background it should continue. */
FS_INLINE float pms_fill_disparity(const FS_GLOBAL float* plane, int source_x, int x, int y,
                                    float max_extrapolation) {
  float at_source = pms_plane_disparity(plane[0], plane[1], plane[2], (float)source_x, (float)y);
  float d = pms_plane_disparity(plane[0], plane[1], plane[2], (float)x, (float)y);
  return FS_FMIN(FS_FMAX(d, at_source - max_extrapolation), at_source + max_extrapolation);
}

/* Occlusion filling (Bleyer et al. 2011, Sec. 3.3): an inconsistent pixel takes the
 * plane of the nearest consistent pixel to its left or right, whichever gives the lower
 * disparity at the pixel (occluded pixels belong to the background), its disparity at
 * the pixel limited to max_extrapolation from the source's own (pms_fill_disparity; the
 * plane keeps its slope and moves). INFINITY gives Bleyer et al.'s plain extrapolation.
 * With no consistent pixel on the row, the pixel keeps its own plane. Writes (a, b, c). */
FS_INLINE void pms_fill_pixel(const FS_GLOBAL float* planes,
                               const FS_GLOBAL unsigned char* consistent, int width, int x,
                               int y, float max_extrapolation, float* abc) {
  int row = y * width;
  int left = x - 1;
  while (left >= 0 && !consistent[row + left]) --left;
  int right = x + 1;
  while (right < width && !consistent[row + right]) ++right;
  int source_x = x;
  float d = 0.0f;
  if (left >= 0 && right < width) {
    float dl = pms_fill_disparity(planes + 4 * (row + left), left, x, y, max_extrapolation);
    float dr = pms_fill_disparity(planes + 4 * (row + right), right, x, y, max_extrapolation);
    source_x = dl <= dr ? left : right;
    d = dl <= dr ? dl : dr;
  } else if (left >= 0 || right < width) {
    source_x = left >= 0 ? left : right;
    d = pms_fill_disparity(planes + 4 * (row + source_x), source_x, x, y, max_extrapolation);
  }
  const FS_GLOBAL float* source = planes + 4 * (row + source_x);
  abc[0] = source[0];
  abc[1] = source[1];
  abc[2] = source[2];
  if (source_x != x &&
      d != pms_plane_disparity(source[0], source[1], source[2], (float)x, (float)y)) {
    /* Limited: the plane through d at (x, y) with the source's slopes. Unlimited
     * planes are copied as they are, so INFINITY reproduces plain extrapolation. */
    abc[2] = d - source[0] * (float)x - source[1] * (float)y;
  }
}

/* Collects the disparities of the window around (x, y) (offsets k*step within
 * -radius..radius, pixels outside the image left out) with their support weights
 * weights[|I_p - I_q|_1]. With `usable` (may be 0: every pixel), only the pixels where it
 * is nonzero vote: the disparities that failed the left/right check are guesses and
 * must not outvote the ones that passed. Disparities above `max_value` do not vote
 * either (the hole filling passes the filled background disparity plus a margin: a hole
 * is background, and the foreground beside it must not bleed in).
 * Returns the number of samples written. */
FS_INLINE int pms_gather_median_samples(const FS_GLOBAL float* disparity,
                                         const FS_GLOBAL unsigned char* usable,
                                         float max_value, const FS_GLOBAL float* color,
                                         const FS_GLOBAL float* weights, int width, int height,
                                         int x, int y, int radius, int step, float* values,
                                         float* sample_weights) {
  const FS_GLOBAL float* centre = color + 4 * (y * width + x);
  int n = 0;
  int first = -(radius / step) * step;
  for (int dy = first; dy <= radius; dy += step) {
    int qy = y + dy;
    if (qy < 0 || qy >= height) continue;
    for (int dx = first; dx <= radius; dx += step) {
      int qx = x + dx;
      if (qx < 0 || qx >= width) continue;
      int q = qy * width + qx;
      if (usable != 0 && !usable[q]) continue;
      if (disparity[q] > max_value) continue;
      values[n] = disparity[q];
      sample_weights[n] = weights[pms_color_l1(centre, color + 4 * q)];
      ++n;
    }
  }
  return n;
}

/*
 * Weighted median of n >= 1 samples (value, weight): the smallest sample value v with
 *   sum of weights of samples with value <= v  >=  half the total weight.
 * Sums always run in sample order, so the answer does not depend on how the caller
 * sorted `sorted_values` (the same values in ascending order); binary search over it is
 * valid because those sums grow with v even in float arithmetic (rounding is monotone).
 */
FS_INLINE float pms_weighted_median(const float* values, const float* weights,
                                     const float* sorted_values, int n) {
  float total = 0.0f;
  for (int i = 0; i < n; ++i) total = total + weights[i];
  float half_total = total * 0.5f;
  int lo = 0;
  int hi = n - 1;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    float v = sorted_values[mid];
    float below = 0.0f;
    for (int i = 0; i < n; ++i) {
      if (values[i] <= v) below = below + weights[i];
    }
    if (below >= half_total) {
      hi = mid;
    } else {
      lo = mid + 1;
    }
  }
  return sorted_values[lo];
}

/* Small segments (speckles): two 4-neighbours belong to one segment when their
 * disparities differ by at most max_step. A segment of fewer than min_size pixels is
 * an island PatchMatch left (one wrong plane that spread a little), too large for the
 * 7x7 final median; it is refilled like a pixel that failed the left/right check.
 * The pair of 4-neighbours (x, y) and (x + 1, y) (horizontal) or (x, y + 1). With
 * follow_slopes the two also join when the step between them continues the step on
 * either side of the pair to within max_step: a steep but smooth surface (a bin wall
 * seen at a grazing angle changes by about 2 px a row) stays one segment instead of
 * falling apart into speckles, while an island of a wrong plane, whose border is a jump
 * unlike the slope on either side, stays cut off. Symmetric in the pair (the steps
 * change sign together), so a search from either end finds the same segments. */
FS_INLINE int pms_segment_pair_joined(const FS_GLOBAL float* disparity, int width, int height,
                                      int x, int y, int horizontal, float max_step,
                                      int follow_slopes) {
  const int stride = horizontal ? 1 : width;
  const int p = y * width + x;
  const int q = p + stride;
  const float step = disparity[q] - disparity[p];
  if (FS_FABS(step) <= max_step) return 1;
  if (!follow_slopes) return 0;
  const int has_before = horizontal ? x >= 1 : y >= 1;
  const int has_after = horizontal ? x + 2 < width : y + 2 < height;
  if (has_before && FS_FABS(step - (disparity[p] - disparity[p - stride])) <= max_step) return 1;
  return has_after && FS_FABS(step - (disparity[q + stride] - disparity[q])) <= max_step;
}

/* The flat plane (0, 0, d): a constant disparity, which pms_fill_pixel copies exactly
 * (0 x + 0 y + d = d), so that refilling a segment takes its neighbour's disparity. */
FS_INLINE void pms_flat_plane(float d, FS_GLOBAL float* plane) {
  plane[0] = 0.0f;
  plane[1] = 0.0f;
  plane[2] = d;
  plane[3] = 0.0f;
}

#endif /* FLEXSIGHT_POSTPROCESS_MATH_H */

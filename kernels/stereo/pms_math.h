/*
 * Per-pixel mathematics of PatchMatch Stereo, shared verbatim by the scalar reference
 * path (fallback/, compiled as C++) and the OpenCL kernels (the .cl files of kernels/, compiled as
 * OpenCL C). Keeping one copy is what makes the two paths give the same bytes.
 *
 * Rules for everything in this file:
 *  - plain float arithmetic written in the order it must be evaluated; both compilers
 *    run with contraction off (-ffp-contract=off, #pragma OPENCL FP_CONTRACT OFF), so
 *    a*b+c is always a rounded product then a rounded sum;
 *  - the only library maths are floor, fabs, fmin/fmax, popcount and sqrt / division,
 *    which are exact or correctly rounded (OpenCL needs -cl-fp32-correctly-rounded-divide-sqrt);
 *    exp() is replaced by a table built once on the host (fallback/stereo/weight_table.h);
 *  - random numbers come from a counter-based hash of (seed, view, pixel, iteration,
 *    trial), so no state is shared between pixels and thread order cannot matter.
 *
 * Buffers are flat float arrays: colour 4 floats per pixel (r, g, b: integer values
 * 0..255; then the pixel's census (at most 24 bits) as an exact float integer), gradient 2 floats per pixel (gx, gy), planes 4 floats per pixel
 * (a, b, c, unused) meaning disparity d(x, y) = a*x + b*y + c in that view's pixels.
 */
#ifndef FLEXSIGHT_PMS_MATH_H
#define FLEXSIGHT_PMS_MATH_H

#include "../common/portability.h"
#include "../common/counter_rng.h"

/* The support-weight table (fallback/stereo/weight_table.h): first exp(-k / gamma) for the L1
 * distance k of two RGB8 colours, an integer in 0..765; then exp(-|(dx, dy)| / gamma_d)
 * for the window offsets, |dx| and |dy| up to 50 (the largest window is 101), row |dy|
 * at PMS_COLOR_WEIGHT_COUNT + |dy| * PMS_DISTANCE_WEIGHT_SIDE. */
#define PMS_COLOR_WEIGHT_COUNT 766
#define PMS_DISTANCE_WEIGHT_SIDE 51
#define PMS_WEIGHT_TABLE_SIZE \
  (PMS_COLOR_WEIGHT_COUNT + PMS_DISTANCE_WEIGHT_SIDE * PMS_DISTANCE_WEIGHT_SIDE)

/* Views. The left view matches at x - d, the right view at x + d. */
#define PMS_VIEW_LEFT 0
#define PMS_VIEW_RIGHT 1

/* Trial keys of the random generator, so that different uses of one (pixel, iteration)
 * never share numbers: 0..2 for the initial plane, then 4 per random-search trial. */
#define PMS_TRIAL_KEY_INIT 0U
#define PMS_TRIAL_KEY_SEARCH 16U

/* Slanted planes steeper than this (|n_z| below it) are not proposed by the random
 * search: they are grazing surfaces that a 35-pixel window cannot match reliably. */
#define PMS_MIN_NORMAL_Z 0.1f

/* Largest |a| and |b| of the random initial planes (disparity change per pixel). */
#define PMS_INIT_MAX_SLOPE 0.5f

typedef struct {
  int radius;            /* half window: its columns span [-radius, radius] */
  int radius_rows;       /* and its rows [-radius_rows, radius_rows] */
  int step;              /* sample every step-th row and column of the window */
  float alpha;           /* weight of the gradient term */
  float one_minus_alpha; /* computed once on the host so both paths use one value */
  float tau_color;
  float tau_gradient;
  float census_weight;   /* weight of the census Hamming distance (0..24) */
  float census_cap;      /* the distance counts at most this many bits (24: no cap) */
} PmsCostParams;

/* ---------------------------------------------------------------- random numbers */

/* The counter-based generator: one independent 32-bit value per key. */
FS_INLINE fs_u32 pms_random_u32(fs_u32 seed, fs_u32 view, fs_u32 pixel,
                                  fs_u32 iteration, fs_u32 trial) {
  fs_u32 h = fs_hash(seed ^ 0x9e3779b9U);
  h = fs_hash(h ^ pixel);
  h = fs_hash(h ^ (iteration * 2U + view));
  h = fs_hash(h ^ trial);
  return h;
}

FS_INLINE float pms_random_unit(fs_u32 seed, fs_u32 view, fs_u32 pixel, fs_u32 iteration,
                                 fs_u32 trial) {
  return fs_u32_to_unit(pms_random_u32(seed, view, pixel, iteration, trial));
}

/* Key of component (0: disparity, 1-3: normal) of random-search trial `trial`. */
FS_INLINE fs_u32 pms_search_trial_key(int trial, int component) {
  return PMS_TRIAL_KEY_SEARCH + 4U * (fs_u32)trial + (fs_u32)component;
}

/* ------------------------------------------------------------------ plane maths */

FS_INLINE float pms_plane_disparity(float a, float b, float c, float x, float y) {
  return a * x + b * y + c;
}

/* Nearest integer, halves rounded up; floor keeps it exact and identical everywhere. */
FS_INLINE float pms_floor_round(float v) { return FS_FLOOR(v + 0.5f); }

/* A random plane through a disparity drawn uniformly in [0, max_disparity] with slopes
 * drawn uniformly in [-PMS_INIT_MAX_SLOPE, PMS_INIT_MAX_SLOPE]. Writes (a, b, c). */
FS_INLINE void pms_random_plane(fs_u32 seed, fs_u32 view, fs_u32 pixel, fs_u32 iteration,
                                 int x, int y, float max_disparity, float* abc) {
  fs_u32 t = PMS_TRIAL_KEY_INIT;
  float d = pms_random_unit(seed, view, pixel, iteration, t + 0U) * max_disparity;
  float a = (pms_random_unit(seed, view, pixel, iteration, t + 1U) * 2.0f - 1.0f) *
            PMS_INIT_MAX_SLOPE;
  float b = (pms_random_unit(seed, view, pixel, iteration, t + 2U) * 2.0f - 1.0f) *
            PMS_INIT_MAX_SLOPE;
  abc[0] = a;
  abc[1] = b;
  abc[2] = d - a * (float)x - b * (float)y;
}

/* Re-expresses a plane of one view in the other view. A left-view point (x, y) with
 * disparity d sees the right-view point (x - d, y) with the same disparity, so
 *   left -> right: d = a (x' + d) + b y + c  =>  d = (a x' + b y + c) / (1 - a)
 *   right -> left: d = a (x - d) + b y + c   =>  d = (a x + b y + c) / (1 + a).
 * Returns 0 (and leaves abc_out alone) when the plane is too steep to transfer. */
FS_INLINE int pms_transfer_plane(const float* abc_in, int from_view, float* abc_out) {
  float denominator = from_view == PMS_VIEW_LEFT ? 1.0f - abc_in[0] : 1.0f + abc_in[0];
  if (!(denominator > 0.05f)) return 0;
  abc_out[0] = abc_in[0] / denominator;
  abc_out[1] = abc_in[1] / denominator;
  abc_out[2] = abc_in[2] / denominator;
  return 1;
}

/* The pixel of the next coarser level (width x height) that fine pixel (x, y) takes its
 * plane or confidence from: (x / 2, y / 2), clamped for odd sizes. */
FS_INLINE int pms_coarse_pixel(int x, int y, int coarse_width, int coarse_height) {
  int cx = x / 2 < coarse_width - 1 ? x / 2 : coarse_width - 1;
  int cy = y / 2 < coarse_height - 1 ? y / 2 : coarse_height - 1;
  return cy * coarse_width + cx;
}

/* Carries a plane from a pyramid level to the next finer one (factor 2). The coarse
 * pixel X covers the fine pixels 2X and 2X+1, so its centre is fine x = 2X + 0.5 and
 * d_fine(x, y) = 2 d_coarse((x - 0.5) / 2, (y - 0.5) / 2):
 * slopes are kept, c becomes 2c - (a + b) / 2. */
FS_INLINE void pms_carry_plane_to_finer(const float* abc_coarse, float* abc_fine) {
  abc_fine[0] = abc_coarse[0];
  abc_fine[1] = abc_coarse[1];
  abc_fine[2] = 2.0f * abc_coarse[2] - 0.5f * (abc_coarse[0] + abc_coarse[1]);
}

/* The random-search candidate: the plane's disparity at (x, y) moved by up to
 * +-disparity_range and its unit normal by up to +-normal_range per component.
 * n = (-a, -b, 1) / |(-a, -b, 1)|; after perturbation only the ratios n_x/n_z and
 * n_y/n_z matter, so the result needs no second normalisation.
 * Returns 0 when the perturbed normal is too steep (see PMS_MIN_NORMAL_Z). */
FS_INLINE int pms_perturb_plane(const float* abc, int x, int y, float max_disparity,
                                 float disparity_range, float normal_range, float u_d,
                                 float u_nx, float u_ny, float u_nz, float* abc_out) {
  float fx = (float)x;
  float fy = (float)y;
  float d = pms_plane_disparity(abc[0], abc[1], abc[2], fx, fy);
  d = d + (u_d * 2.0f - 1.0f) * disparity_range;
  d = FS_FMIN(FS_FMAX(d, 0.0f), max_disparity);
  float inv_norm = 1.0f / FS_SQRT(abc[0] * abc[0] + abc[1] * abc[1] + 1.0f);
  float nx = -abc[0] * inv_norm + (u_nx * 2.0f - 1.0f) * normal_range;
  float ny = -abc[1] * inv_norm + (u_ny * 2.0f - 1.0f) * normal_range;
  float nz = inv_norm + (u_nz * 2.0f - 1.0f) * normal_range;
  float length = FS_SQRT(nx * nx + ny * ny + nz * nz);
  if (!(nz > PMS_MIN_NORMAL_Z * length)) return 0;
  float a = -nx / nz;
  float b = -ny / nz;
  abc_out[0] = a;
  abc_out[1] = b;
  abc_out[2] = d - a * fx - b * fy;
  return 1;
}

/* Spatial propagation candidates of a checkerboard schedule: the 4-neighbours at
 * distances 1, 5, 15 and 45, nearest first. Odd distances keep every candidate on the
 * other parity. Through the neighbours at 1 and 5 px a plane travels at most five pixels
 * per half-step; the far ones let good planes cross a textureless wall or an occluded
 * band in a few half-steps, and offer each pixel planes from other parts of its surface
 * (Pipes, Jadeplant and PianoL gain most). The far rings take about 0.6 points off
 * bad-2 on the 15 MiddEval3 Q scenes, in 1.4x the time of 1 and 5 alone (the sweep is
 * in docs/tuning-log.md). */
#define PMS_SPATIAL_CANDIDATES 16
FS_INLINE void pms_spatial_offset(int candidate, int* dx, int* dy) {
  int ring = candidate >> 2;
  int distance = ring == 0 ? 1 : (ring == 1 ? 5 : (ring == 2 ? 15 : 45));
  int direction = candidate & 3;
  *dx = direction == 0 ? -distance : (direction == 1 ? distance : 0);
  *dy = direction == 2 ? -distance : (direction == 3 ? distance : 0);
}

/* PPMS's confidence rules. A pixel is confident where the coarser level's (or, after
 * a refresh, its own level's) left/right confidence reaches the threshold. */
FS_INLINE int pms_is_confident(float confidence, float threshold) {
  return confidence >= threshold;
}

/* A confident pixel tries only the first `confident_candidates` spatial candidates, the
 * near rings. The far candidates exist to carry planes across textureless or occluded
 * areas whose planes are wrong, and a confident pixel's carried plane is already within
 * a pixel or two of the answer. The kernels split the candidate loop at
 * confident_candidates instead (every pixel, then only the unsure ones: the same order
 * per pixel). */
FS_INLINE int pms_spatial_candidate_tried(int candidate, int confident,
                                           int confident_candidates) {
  return !confident || candidate < confident_candidates;
}

/* Random search schedule: trial k may move the disparity by initial_range / 2^k and
 * each normal component by normal_range / 2^k; trials run while the disparity range
 * is at least min_range. */
FS_INLINE int pms_search_trial_count(float initial_range, float min_range) {
  int count = 0;
  for (float range = initial_range; range >= min_range && count < 30; range = range * 0.5f) {
    ++count;
  }
  return count;
}

/* A confident pixel skips the trials whose range exceeds max_range: since the ranges
 * halve, the first ones. Their count, of `trials` (the kernels run those trials for the
 * unsure pixels only, then the rest for every pixel: the same order per pixel). */
FS_INLINE int pms_search_wide_trial_count(float initial_range, int trials, float max_range) {
  int count = 0;
  for (float range = initial_range; count < trials && range > max_range; range = range * 0.5f) {
    ++count;
  }
  return count;
}

/* --------------------------------------------------------------- matching cost */

/* Index of the support-weight table for two RGB8 colours stored as floats. */
FS_INLINE int pms_color_l1(const FS_GLOBAL float* p, const FS_GLOBAL float* q) {
  return (int)(FS_FABS(p[0] - q[0]) + FS_FABS(p[1] - q[1]) + FS_FABS(p[2] - q[2]));
}

/* Row |dy| of the distance weights: entry |dx| is the weight of window offset (dx, dy). */
FS_INLINE const FS_GLOBAL float* pms_distance_weight_row(const FS_GLOBAL float* weights,
                                                           int dy) {
  return weights + PMS_COLOR_WEIGHT_COUNT + (dy < 0 ? -dy : dy) * PMS_DISTANCE_WEIGHT_SIDE;
}

/* First window offset at or after max(-radius, lowest) on the grid k*step (the grid
 * goes through 0 so the centre pixel is always sampled). lowest <= 0. */
FS_INLINE int pms_first_offset(int radius, int step, int lowest) {
  int low = lowest > -radius ? lowest : -radius;
  return -((-low) / step) * step;
}

/* The window's rows in the order the costs sum them: the centre row, then outwards,
 * above before below (0, -step, +step, -2 step, ...); row_index runs over
 * 0 .. pms_window_row_count - 1 and rows outside [y_begin, y_end] are skipped. The rows
 * near the centre carry most of the support weight, so a losing plane's partial sum
 * reaches its bound after fewer rows than in top-to-bottom order. */
FS_INLINE int pms_window_row_count(int radius, int step) { return 2 * (radius / step) + 1; }
FS_INLINE int pms_window_row(int row_index, int step) {
  int ring = (row_index + 1) >> 1;
  return (row_index & 1) ? -ring * step : ring * step;
}

/* The window offsets of pixel (px, py) that lie inside the image, on the grid k*step:
 * dy in [y_begin, y_end], dx in [x_begin, x_end]. Every window sum uses these, so the
 * cost and its weight sum run over the same pixels. */
FS_INLINE void pms_window_bounds(PmsCostParams params, int width, int height, int px, int py,
                                  int* y_begin, int* y_end, int* x_begin, int* x_end) {
  *y_begin = pms_first_offset(params.radius_rows, params.step, -py);
  *y_end = params.radius_rows < height - 1 - py ? params.radius_rows : height - 1 - py;
  *x_begin = pms_first_offset(params.radius, params.step, -px);
  *x_end = params.radius < width - 1 - px ? params.radius : width - 1 - px;
}

/* One window sample of the matching cost, shared by the scalar cost (pms_plane_cost,
 * which the reference path runs) and the kernels' lane cost (pms_cost_lanes_group in
 * pms_kernel_support.h, several pixels per work item in OpenCL vector types). These are
 * macros because the same expression must serve float and floatN; both sides call them
 * with the same operands in the same order, so the two costs cannot differ in a bit
 * (contraction is off on both sides). */

/* Disparity of plane (a, b, c) at window column qx (a float) of a row whose b * qy is
 * row_term. */
#define PMS_SAMPLE_DISPARITY(a, qx, row_term, c) ((a) * (qx) + (row_term) + (c))

/* Where the sample with disparity d matches in the other view: qx -+ d (direction -1
 * for the left view, +1 for the right), clamped into the row [0, max_x]. */
#define PMS_MATCH_X(qx, direction, d, max_x) \
  FS_FMIN(FS_FMAX((qx) + (direction) * (d), 0.0f), (max_x))

/* Linear interpolation between m0 and m1 at t, given the step m1 - m0. */
#define PMS_LERP(m0, t, step) ((m0) + (t) * (step))

/* L1 differences of a colour (three channels) and of a gradient (two components). */
#define PMS_COLOR_DIFF(q0, q1, q2, m0, m1, m2) \
  (FS_FABS((q0) - (m0)) + FS_FABS((q1) - (m1)) + FS_FABS((q2) - (m2)))
#define PMS_GRADIENT_DIFF(g0, g1, m0, m1) (FS_FABS((g0) - (m0)) + FS_FABS((g1) - (m1)))

/* A sample's dissimilarity: the truncated colour and gradient terms (Bleyer et al.
 * 2011, eq. 3) plus the census Hamming distance (bits, a float) capped at census_cap. */
#define PMS_DISSIMILARITY(params, color_diff, grad_diff, census_bits)                  \
  ((params).one_minus_alpha * FS_FMIN((color_diff), (params).tau_color) +              \
   (params).alpha * FS_FMIN((grad_diff), (params).tau_gradient) +                      \
   (params).census_weight * FS_FMIN((census_bits), (params).census_cap))

/*
 * Adaptive-support-weighted matching cost of plane (a, b, c) at pixel (px, py) of the
 * reference view against the other view (Bleyer et al. 2011, eq. 2-4, plus a census term):
 *   sum over window pixels q of  w(p, q) * [ (1 - alpha) min(|I_q - I'_q'|_1, tau_col)
 *                                           + alpha min(|grad I_q - grad I'_q'|_1, tau_grad)
 *                                           + census_weight * min(H(census_q, census'_q''),
 *                                                                 census_cap) ]
 * with w(p, q) = exp(-|I_p - I_q|_1 / gamma) exp(-|q - p| / gamma_d) (Yoon and Kweon's
 * adaptive support weight; both factors from the `weights` table), q' = q -+ d(q)
 * (direction -1 for the left view, +1 for the right), I' linearly interpolated, H the
 * Hamming distance of census bit strings (pms_census_pixel, 5x5 by default) and q'' the pixel nearest
 * to q' (a bit string does not interpolate).
 * Window pixels outside the image are left out; the set depends only on p, so every
 * candidate plane of p is summed over the same pixels. Matching positions outside the
 * other image are clamped to its border.
 *
 * Rows are summed centre first (pms_window_row). The sum stops as soon as it reaches
 * `bound` (every term is >= 0, so the final sum could only be larger): the caller
 * rejects any result >= its best cost anyway. Pass a huge bound for the full cost.
 */
FS_INLINE float pms_plane_cost(const FS_GLOBAL float* ref_color,
                                const FS_GLOBAL float* ref_grad,
                                const FS_GLOBAL float* other_color,
                                const FS_GLOBAL float* other_grad,
                                const FS_GLOBAL float* weights, int width, int height,
                                PmsCostParams params, int px, int py, float a, float b,
                                float c, float direction, float bound) {
  const FS_GLOBAL float* centre = ref_color + 4 * (py * width + px);
  int y_begin, y_end, x_begin, x_end;
  pms_window_bounds(params, width, height, px, py, &y_begin, &y_end, &x_begin, &x_end);
  float max_x = (float)(width - 1);
  float sum = 0.0f;
  int row_count = pms_window_row_count(params.radius_rows, params.step);
  for (int row_index = 0; row_index < row_count; ++row_index) {
    int dy = pms_window_row(row_index, params.step);
    if (dy < y_begin || dy > y_end) continue;
    int qy = py + dy;
    float row_term = b * (float)qy;
    const FS_GLOBAL float* ref_row = ref_color + 4 * qy * width;
    const FS_GLOBAL float* ref_grad_row = ref_grad + 2 * qy * width;
    const FS_GLOBAL float* other_row = other_color + 4 * qy * width;
    const FS_GLOBAL float* other_grad_row = other_grad + 2 * qy * width;
    const FS_GLOBAL float* distance_weights = pms_distance_weight_row(weights, dy);
    for (int dx = x_begin; dx <= x_end; dx += params.step) {
      int qx = px + dx;
      float d = PMS_SAMPLE_DISPARITY(a, (float)qx, row_term, c);
      float match_x = PMS_MATCH_X((float)qx, direction, d, max_x);
      float x0f = FS_FLOOR(match_x);
      int x0 = (int)x0f;
      int x1 = x0 + 1 < width ? x0 + 1 : x0;
      float t = match_x - x0f;
      const FS_GLOBAL float* q = ref_row + 4 * qx;
      const FS_GLOBAL float* m0 = other_row + 4 * x0;
      const FS_GLOBAL float* m1 = other_row + 4 * x1;
      float color_diff = PMS_COLOR_DIFF(q[0], q[1], q[2], PMS_LERP(m0[0], t, m1[0] - m0[0]),
                                        PMS_LERP(m0[1], t, m1[1] - m0[1]),
                                        PMS_LERP(m0[2], t, m1[2] - m0[2]));
      const FS_GLOBAL float* g = ref_grad_row + 2 * qx;
      const FS_GLOBAL float* g0 = other_grad_row + 2 * x0;
      const FS_GLOBAL float* g1 = other_grad_row + 2 * x1;
      float grad_diff = PMS_GRADIENT_DIFF(g[0], g[1], PMS_LERP(g0[0], t, g1[0] - g0[0]),
                                          PMS_LERP(g0[1], t, g1[1] - g0[1]));
      const FS_GLOBAL float* mn = t < 0.5f ? m0 : m1;
      float census_bits = (float)FS_POPCOUNT((fs_u32)q[3] ^ (fs_u32)mn[3]);
      float dissimilarity = PMS_DISSIMILARITY(params, color_diff, grad_diff, census_bits);
      float w = weights[pms_color_l1(centre, q)] * distance_weights[dx < 0 ? -dx : dx];
      sum = sum + w * dissimilarity;
    }
    if (sum >= bound) return sum;
  }
  return sum;
}

/*
 * Sum of the support weights over the window samples of pms_plane_cost at (px, py):
 * dividing a cost by it gives the weighted mean dissimilarity, comparable between
 * textured and uniform regions (the confidence map uses it).
 */
FS_INLINE float pms_support_weight_sum(const FS_GLOBAL float* ref_color,
                                        const FS_GLOBAL float* weights, int width, int height,
                                        PmsCostParams params, int px, int py) {
  const FS_GLOBAL float* centre = ref_color + 4 * (py * width + px);
  int y_begin, y_end, x_begin, x_end;
  pms_window_bounds(params, width, height, px, py, &y_begin, &y_end, &x_begin, &x_end);
  float sum = 0.0f;
  for (int dy = y_begin; dy <= y_end; dy += params.step) {
    const FS_GLOBAL float* ref_row = ref_color + 4 * (py + dy) * width;
    const FS_GLOBAL float* distance_weights = pms_distance_weight_row(weights, dy);
    for (int dx = x_begin; dx <= x_end; dx += params.step) {
      sum = sum + weights[pms_color_l1(centre, ref_row + 4 * (px + dx))] *
                      distance_weights[dx < 0 ? -dx : dx];
    }
  }
  return sum;
}

/* The images the costs read (colour with census, gradient, match records) are made
 * by pms_image.h. */
#include "pms_image.h"

#endif /* FLEXSIGHT_PMS_MATH_H */

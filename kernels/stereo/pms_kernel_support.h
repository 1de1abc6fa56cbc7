/*
 * Helpers of the OpenCL kernels only (never compiled as C++): the work-item to pixel
 * mapping, the cost call with the kernels' common arguments, the best-plane
 * bookkeeping of the reference's BestPlane (fallback/stereo/patchmatch_reference.cpp).
 * Several pixels per work item: pms_lanes.h; the lane cost: pms_lane_cost.h.
 */
#ifndef FLEXSIGHT_PMS_KERNEL_SUPPORT_H
#define FLEXSIGHT_PMS_KERNEL_SUPPORT_H

#include "pms_math.h"

/* The largest float: the "no bound" of a full cost (std::numeric_limits<float>::max()). */
#define PMS_NO_BOUND FLT_MAX

/* The leading arguments of every kernel that evaluates matching costs, in the order the
 * host sets them (OpenClStages::set_cost_args): the view's images, the other view's
 * match records (pack_match_samples), the weight table, the level size, the cost
 * parameters and the view. */
#define PMS_COST_KERNEL_ARGS                                                             \
  const __global float *ref_color, const __global float *ref_grad,                       \
      const __global float *other_match, const __global float *weights, int width,       \
      int height, PmsCostParams cost_params, int view

/* Everything pms_cost_lanes_group needs besides the pixels and the planes. */
typedef struct {
  const __global float* ref_color;
  const __global float* ref_grad;
  const __global float* other_match;
  const __global float* weights;
  int width;
  int height;
  PmsCostParams params;
  float direction; /* -1 left view (matches at x - d), +1 right view */
} PmsCostInputs;

#define PMS_COST_INPUTS()                                                                \
  {ref_color, ref_grad, other_match, weights, width, height, cost_params,                 \
   view == PMS_VIEW_LEFT ? -1.0f : 1.0f}

/* Pixel of a work item of a checkerboard stage: the global size is (ceil(width / 2),
 * height) and item (i, y) handles x = 2 i + (y + parity) % 2, the reference's loop.
 * Returns 0 for the items past the right edge (odd widths) or below the last row. */
inline int pms_checker_pixel(int width, int height, int parity, int* x, int* y) {
  *y = (int)get_global_id(1);
  *x = 2 * (int)get_global_id(0) + ((*y + parity) & 1);
  return *x < width && *y < height;
}

/* Pixel of a work item of a dense stage (global size rounded up to the work group). */
inline int pms_dense_pixel(int width, int height, int* x, int* y) {
  *x = (int)get_global_id(0);
  *y = (int)get_global_id(1);
  return *x < width && *y < height;
}

inline void pms_load_plane(const __global float* planes, int index, float* abc) {
  abc[0] = planes[4 * index];
  abc[1] = planes[4 * index + 1];
  abc[2] = planes[4 * index + 2];
}

/* The best plane found so far for one pixel while a stage tries candidates; the same
 * rules as the reference's BestPlane, so that costs are written exactly when it does. */
typedef struct {
  float abc[3];
  float cost;
  int changed;
} PmsBestPlane;

inline PmsBestPlane pms_best_load(const __global float* planes, const __global float* cost,
                                  int index) {
  PmsBestPlane best;
  pms_load_plane(planes, index, best.abc);
  best.cost = cost[index];
  best.changed = 0;
  return best;
}

/* Bitwise, as the reference's memcmp: 0.0f and -0.0f differ, and so do NaNs. */
inline int pms_best_same_as(const PmsBestPlane* best, const float* candidate) {
  return as_uint(best->abc[0]) == as_uint(candidate[0]) &&
         as_uint(best->abc[1]) == as_uint(candidate[1]) &&
         as_uint(best->abc[2]) == as_uint(candidate[2]);
}

inline void pms_best_offer(PmsBestPlane* best, const float* candidate, float candidate_cost) {
  if (candidate_cost < best->cost) {
    best->abc[0] = candidate[0];
    best->abc[1] = candidate[1];
    best->abc[2] = candidate[2];
    best->cost = candidate_cost;
    best->changed = 1;
  }
}

/* Writes nothing when no candidate won: the fourth plane component and the cost keep
 * their bytes, as in the reference. */
inline void pms_best_store(const PmsBestPlane* best, __global float* planes, __global float* cost,
                           int index) {
  if (!best->changed) return;
  planes[4 * index] = best->abc[0];
  planes[4 * index + 1] = best->abc[1];
  planes[4 * index + 2] = best->abc[2];
  cost[index] = best->cost;
}

#endif /* FLEXSIGHT_PMS_KERNEL_SUPPORT_H */

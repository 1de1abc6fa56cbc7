/*
 * Several pixels per OpenCL work item (never compiled as C++): the vector types of
 * PMS_LANES lanes, the mapping of a work item to its lanes (a checkerboard parity, a
 * dense row, or a list of pixels) and the start of the search stages.
 */
#ifndef FLEXSIGHT_PMS_LANES_H
#define FLEXSIGHT_PMS_LANES_H

#include "pms_kernel_support.h"

/* ------------------------------------------------- lanes: several pixels per item
 *
 * The cost kernels spend nearly all their time in pms_plane_cost. A CPU OpenCL driver
 * (PoCL) cannot vectorise it across work items (its loops and early exits differ from
 * pixel to pixel), so the hot kernels let each work item handle PMS_LANES pixels of one
 * row and evaluate their costs together in vector types, one pixel per lane.
 *
 * Exactness: each lane performs pms_plane_cost's float operations in its order (the
 * same expressions, component-wise; contraction is off), summing the window pixels
 * inside the image in the same order; samples outside the image leave the lane's sum
 * untouched (select, not "+ 0"). The only difference is the early exit: pms_plane_cost
 * stops a row after its sum reaches `bound`, the lanes stop after every lane's has.
 * Every term is >= 0 and rounding is monotone, so a lane that reached its bound ends
 * >= bound either way and its caller (which keeps only costs < bound) rejects it
 * either way; a lane that never reaches its bound sums the whole window, as the
 * scalar function does. The host sets PMS_LANES (OpenClStages). */
#ifndef PMS_LANES
#define PMS_LANES 8
#endif
/* PMS_LANES 1 is for GPUs, which run work items side by side in hardware and so need
 * many items more than wide ones: one pixel per item, plain scalars. Scalar comparisons
 * give 1 where vector ones give -1, hence PMS_ANY / PMS_ALL (select() takes either). */
#if PMS_LANES == 1
typedef float pms_floatv;
typedef int pms_intv;
#define PMS_VLOAD(offset, p) ((p)[offset])
#define PMS_TO_FLOATV(v) ((float)(v))
#define PMS_TO_INTV(v) ((int)(v))
#define PMS_TO_UINTV(v) ((uint)(v))
#define PMS_LANE(v, l) (v)
#define PMS_ANY(v) ((v) != 0)
#define PMS_ALL(v) ((v) != 0)
#elif PMS_LANES == 4
typedef float4 pms_floatv;
typedef int4 pms_intv;
#define PMS_VLOAD vload4
#define PMS_TO_FLOATV convert_float4
#define PMS_TO_INTV convert_int4
#define PMS_TO_UINTV convert_uint4
#elif PMS_LANES == 8
typedef float8 pms_floatv;
typedef int8 pms_intv;
#define PMS_VLOAD vload8
#define PMS_TO_FLOATV convert_float8
#define PMS_TO_INTV convert_int8
#define PMS_TO_UINTV convert_uint8
#elif PMS_LANES == 16
typedef float16 pms_floatv;
typedef int16 pms_intv;
#define PMS_VLOAD vload16
#define PMS_TO_FLOATV convert_float16
#define PMS_TO_INTV convert_int16
#define PMS_TO_UINTV convert_uint16
#else
#error "PMS_LANES must be 1, 4, 8 or 16"
#endif
#if PMS_LANES > 1
#define PMS_LANE(v, l) ((v)[l])
#define PMS_ANY(v) any(v)
#define PMS_ALL(v) all(v)
#endif

/* Eight floats base[index.s0], ..., base[index.s7] (a gather). */
#define PMS_GATHER8(base, index)                                                    \
  ((float8)((base)[(index).s0], (base)[(index).s1], (base)[(index).s2], (base)[(index).s3], \
            (base)[(index).s4], (base)[(index).s5], (base)[(index).s6], (base)[(index).s7]))

/* Per-lane state of a lane kernel: its pixel (x clamped into the row for lanes past
 * the right edge, which are inactive: they compute but never write). */
typedef struct {
  int x[PMS_LANES];
  int active[PMS_LANES];
  int first;  /* unclamped x of lane 0; lane l's is first + stride * l */
  int stride; /* 2 for checkerboard lanes, 1 for dense ones, 0 for listed ones */
} PmsLanes;

/* Lanes of a checkerboard item: the global size is (ceil(ceil(width / 2) / PMS_LANES),
 * height); item (i, y) handles x = 2 (PMS_LANES i + lane) + (y + parity) % 2.
 * Returns 0 when no lane has a pixel. */
inline int pms_checker_lanes(int width, int height, int parity, PmsLanes* lanes, int* y) {
  *y = (int)get_global_id(1);
  if (*y >= height) return 0;
  int first = 2 * PMS_LANES * (int)get_global_id(0) + ((*y + parity) & 1);
  if (first >= width) return 0;
  lanes->first = first;
  lanes->stride = 2;
  for (int l = 0; l < PMS_LANES; ++l) {
    int x = first + 2 * l;
    lanes->active[l] = x < width;
    lanes->x[l] = x < width ? x : width - 1;
  }
  return 1;
}

/* Lanes of a dense item: global size (ceil(width / PMS_LANES), height). */
inline int pms_dense_lanes(int width, int height, PmsLanes* lanes, int* y) {
  *y = (int)get_global_id(1);
  if (*y >= height) return 0;
  int first = PMS_LANES * (int)get_global_id(0);
  if (first >= width) return 0;
  lanes->first = first;
  lanes->stride = 1;
  for (int l = 0; l < PMS_LANES; ++l) {
    int x = first + l;
    lanes->active[l] = x < width;
    lanes->x[l] = x < width ? x : width - 1;
  }
  return 1;
}

/* Lanes of a listed item: row y's list of pixels (list_unsure_pixels.cl: list +
 * y * list_stride, counts[y] of them), PMS_LANES consecutive entries per item; the global
 * size is (ceil(list_stride / PMS_LANES), height). Lanes past the row's count are
 * inactive and take the last listed pixel. The pixels are in no fixed pattern, so the
 * cost reads them lane by lane (stride 0). Returns 0 when no lane has a pixel. */
inline int pms_listed_lanes(const __global int* list, const __global int* counts,
                            int list_stride, int height, PmsLanes* lanes, int* y) {
  *y = (int)get_global_id(1);
  if (*y >= height) return 0;
  const int count = counts[*y];
  const int first = PMS_LANES * (int)get_global_id(0);
  if (first >= count) return 0;
  const __global int* row_list = list + *y * list_stride;
  for (int l = 0; l < PMS_LANES; ++l) {
    lanes->active[l] = first + l < count;
    lanes->x[l] = row_list[first + l < count ? first + l : count - 1];
  }
  lanes->first = lanes->x[0];
  lanes->stride = 0;
  return 1;
}

/* The lanes of a checkerboard stage: the whole parity when `list` is NULL, otherwise the
 * listed pixels of the parity. */
inline int pms_stage_lanes(int width, int height, int parity, const __global int* list,
                           const __global int* counts, int list_stride, PmsLanes* lanes,
                           int* y) {
  if (list == 0) return pms_checker_lanes(width, height, parity, lanes, y);
  return pms_listed_lanes(list, counts, list_stride, height, lanes, y);
}

/* The trailing arguments of the checkerboard search stages (propagate_spatial,
 * propagate_view, refine_random), in the order the host sets them: the listed pixels
 * (list_unsure_pixels.cl; `list` NULL for the whole parity), then the view's planes and
 * costs. */
#define PMS_SEARCH_STAGE_ARGS                                                          \
  const __global int *list, const __global int *list_counts, int list_stride,            \
      __global float *planes, __global float *cost

/* The start of a search stage's work item: its lanes (pms_stage_lanes) and each lane's
 * best plane so far. Returns 0 when the item has no pixel. A kernel passes its own
 * arguments as PMS_SEARCH_STAGE_INPUTS. */
#define PMS_SEARCH_STAGE_INPUTS \
  width, height, parity, list, list_counts, list_stride, planes, cost
inline int pms_search_begin(int width, int height, int parity, const __global int* list,
                            const __global int* list_counts, int list_stride,
                            const __global float* planes, const __global float* cost,
                            PmsLanes* lanes, int* y, PmsBestPlane* best) {
  if (!pms_stage_lanes(width, height, parity, list, list_counts, list_stride, lanes, y)) {
    return 0;
  }
  for (int l = 0; l < PMS_LANES; ++l) {
    best[l] = pms_best_load(planes, cost, *y * width + lanes->x[l]);
  }
  return 1;
}

#endif /* FLEXSIGHT_PMS_LANES_H */

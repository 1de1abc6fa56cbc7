/* Small segments (postprocess_math.h: pms_segment_pair_joined), found by label propagation
 * with union-find roots (reference: large_segment_mask, a breadth-first search; both
 * give the same mask because a segment's pixels are the same whatever finds them).
 *
 * Every pixel's label points at a pixel of its own segment with an index no larger
 * than its own, so following labels ends at a root (label == index). segment_merge
 * links the larger of two neighbouring roots under the smaller (atomic_min, so
 * concurrent links keep the smallest) and the host repeats merge and flatten until a
 * merge changes nothing; then each segment has one root, its smallest index, whatever
 * the order the work items ran in. */
#include "postprocess_math.h"
#include "pms_kernel_support.h"

inline int pms_segment_root(volatile __global int* labels, int p) {
  int root = labels[p];
  while (labels[root] != root) root = labels[root];
  return root;
}

__kernel void segment_init(int width, int height, __global int* labels, __global int* counts) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  labels[y * width + x] = y * width + x;
  counts[y * width + x] = 0;
}

/* Joins each pixel with its right and lower neighbour (that covers every 4-neighbour
 * pair once). */
__kernel void segment_merge(const __global float* disparity, int width, int height,
                            float max_step, int follow_slopes, volatile __global int* labels,
                            __global int* changed) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  const int p = y * width + x;
  const int neighbours[2] = {x + 1 < width ? p + 1 : -1, y + 1 < height ? p + width : -1};
  for (int k = 0; k < 2; ++k) {
    const int q = neighbours[k];
    if (q < 0 || !pms_segment_pair_joined(disparity, width, height, x, y, k == 0, max_step,
                                          follow_slopes)) {
      continue;
    }
    const int root_p = pms_segment_root(labels, p);
    const int root_q = pms_segment_root(labels, q);
    if (root_p == root_q) continue;
    atomic_min(&labels[root_p > root_q ? root_p : root_q], root_p < root_q ? root_p : root_q);
    *changed = 1;
  }
}

__kernel void segment_flatten(int width, int height, volatile __global int* labels) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  labels[y * width + x] = pms_segment_root(labels, y * width + x);
}

__kernel void segment_count(int width, int height, const __global int* labels,
                            __global int* counts) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  atomic_inc(&counts[labels[y * width + x]]);
}

__kernel void segment_large_mask(int width, int height, const __global int* labels,
                                 const __global int* counts, int min_size,
                                 __global uchar* large) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  const int p = y * width + x;
  large[p] = counts[labels[p]] >= min_size ? 1 : 0;
}

/* mask &= other, per pixel (reference: mask_and). */
__kernel void mask_and(const __global uchar* other, int width, int height,
                       __global uchar* mask) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  const int p = y * width + x;
  mask[p] = mask[p] && other[p] ? 1 : 0;
}

/* (0, 0, d, 0) per pixel (reference: flat_planes). */
__kernel void flat_planes(const __global float* disparity, int width, int height,
                          __global float* planes) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  pms_flat_plane(disparity[y * width + x], planes + 4 * (y * width + x));
}

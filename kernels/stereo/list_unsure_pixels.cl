/* The pixels of one checkerboard parity that are not confident, row by row: the work list
 * of the search steps that only they take (the far spatial candidates, the wide random
 * trials). A work item per row scans its pixels of the parity; row y's list starts at
 * list + y * list_stride and has counts[y] entries. No reference counterpart: the
 * reference tests each pixel's confidence inside its loops (pms_spatial_candidate_tried),
 * the kernels run the unsure pixels' extra steps as a separate launch over this list, so
 * that the vector lanes of a work item are not held up by one unsure pixel among
 * confident ones. */
#include "pms_math.h"

__kernel void list_unsure_pixels(const __global float* confidence, int width, int height,
                                 int parity, float confident_threshold, int list_stride,
                                 __global int* list, __global int* counts) {
  const int y = (int)get_global_id(0);
  if (y >= height) return;
  __global int* row_list = list + y * list_stride;
  int count = 0;
  for (int x = (y + parity) & 1; x < width; x += 2) {
    if (!pms_is_confident(confidence[y * width + x], confident_threshold)) row_list[count++] = x;
  }
  counts[y] = count;
}

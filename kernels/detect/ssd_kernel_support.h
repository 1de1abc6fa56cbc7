/*
 * What the detection kernels share and the reference does not need (never compiled as
 * C++): the work item's place in its launch.
 */
#ifndef FLEXSIGHT_SSD_KERNEL_SUPPORT_H
#define FLEXSIGHT_SSD_KERNEL_SUPPORT_H

#include "ssd_math.h"

/* The work item's (i, j) in a launch over width x height items; 0 for the items the
 * host's rounding up to whole work groups adds, in both dimensions (a launch over
 * (anchors, 1) still has work groups several items tall). */
inline int ssd_work_item(int width, int height, int* i, int* j) {
  *i = (int)get_global_id(0);
  *j = (int)get_global_id(1);
  return *i < width && *j < height;
}

/* The work item's index i in a launch over `count` items laid out as SSD_LINEAR_ROWS
 * rows of ceil(count / rows); 0 for the items past them. */
inline int ssd_linear_item(int count, int* i) {
  int row_length = (count + SSD_LINEAR_ROWS - 1) / SSD_LINEAR_ROWS;
  int x = (int)get_global_id(0);
  int y = (int)get_global_id(1);
  *i = y * row_length + x;
  return x < row_length && y < SSD_LINEAR_ROWS && *i < count;
}

#endif /* FLEXSIGHT_SSD_KERNEL_SUPPORT_H */

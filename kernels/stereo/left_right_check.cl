/* 1 where the disparity of `view` and the other view's disparity it points at agree
 * within `tolerance` (reference: left_right_check). */
#include "postprocess_math.h"
#include "pms_kernel_support.h"

__kernel void left_right_check(const __global float* disparity,
                               const __global float* other_disparity, int width, int height,
                               int view, float tolerance, __global uchar* consistent) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  consistent[y * width + x] = (uchar)pms_lr_consistent(disparity, other_disparity, width, x, y,
                                                       view == PMS_VIEW_LEFT ? -1.0f : 1.0f,
                                                       tolerance);
}

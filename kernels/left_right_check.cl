/* 1 where the left disparity and the right disparity it points at agree within
 * `tolerance` (reference: left_right_check). */
#include "postprocess_math.h"
#include "pms_kernel_support.h"

__kernel void left_right_check(const __global float* left_disparity,
                               const __global float* right_disparity, int width, int height,
                               float tolerance, __global uchar* consistent) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  consistent[y * width + x] = (uchar)pms_lr_consistent(left_disparity, right_disparity, width,
                                                       x, y, -1.0f, tolerance);
}

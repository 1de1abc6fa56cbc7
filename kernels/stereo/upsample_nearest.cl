/* Confidence of the next finer level: fine pixel (x, y) takes coarse pixel
 * (x / 2, y / 2), clamped for odd sizes (reference: upsample_nearest). */
#include "pms_kernel_support.h"

__kernel void upsample_nearest(const __global float* coarse, int coarse_width,
                               int coarse_height, __global float* fine, int fine_width,
                               int fine_height) {
  int x, y;
  if (!pms_dense_pixel(fine_width, fine_height, &x, &y)) return;
  fine[y * fine_width + x] = coarse[pms_coarse_pixel(x, y, coarse_width, coarse_height)];
}

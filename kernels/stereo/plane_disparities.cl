/* d = a x + b y + c at every pixel (reference: plane_disparities). */
#include "pms_kernel_support.h"

__kernel void plane_disparities(const __global float* planes, int width, int height,
                                __global float* disparity) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  int index = y * width + x;
  disparity[index] = pms_plane_disparity(planes[4 * index], planes[4 * index + 1],
                                         planes[4 * index + 2], (float)x, (float)y);
}

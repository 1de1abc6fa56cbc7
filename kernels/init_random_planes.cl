/* A random plane for every pixel of one view, then its full cost
 * (reference: init_random_planes). The fourth plane component is written as 0, the
 * value the reference's PlaneField::resize leaves there. */
#include "pms_kernel_support.h"

__kernel void init_random_planes(PMS_COST_KERNEL_ARGS, uint seed, uint iteration,
                                 float max_disparity, __global float* planes,
                                 __global float* cost) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  int index = y * width + x;
  float abc[3];
  pms_random_plane(seed, (uint)view, (uint)index, iteration, x, y, max_disparity, abc);
  planes[4 * index] = abc[0];
  planes[4 * index + 1] = abc[1];
  planes[4 * index + 2] = abc[2];
  planes[4 * index + 3] = 0.0f;
  cost[index] = pms_cost_at(&in, x, y, abc, PMS_NO_BOUND);
}

/* Full cost of the plane every pixel already holds, after carrying planes from a
 * coarser level (reference: evaluate_costs). */
#include "pms_kernel_support.h"

__kernel void evaluate_costs(PMS_COST_KERNEL_ARGS, const __global float* planes,
                             __global float* cost) {
  int x, y;
  if (!pms_dense_pixel(width, height, &x, &y)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  int index = y * width + x;
  float abc[3];
  pms_load_plane(planes, index, abc);
  cost[index] = pms_cost_at(&in, x, y, abc, PMS_NO_BOUND);
}

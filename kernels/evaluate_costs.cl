/* Full cost of the plane every pixel already holds, after carrying planes from a
 * coarser level (reference: evaluate_costs). Each work item handles PMS_LANES
 * consecutive pixels of a row (pms_dense_lanes). */
#include "pms_kernel_support.h"

__kernel void evaluate_costs(PMS_COST_KERNEL_ARGS, const __global float* planes,
                             __global float* cost) {
  PmsLanes lanes;
  int y;
  if (!pms_dense_lanes(width, height, &lanes, &y)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  float ca[PMS_LANES], cb[PMS_LANES], cc[PMS_LANES], bound[PMS_LANES];
  for (int l = 0; l < PMS_LANES; ++l) {
    float abc[3];
    pms_load_plane(planes, y * width + lanes.x[l], abc);
    ca[l] = abc[0];
    cb[l] = abc[1];
    cc[l] = abc[2];
    bound[l] = lanes.active[l] ? PMS_NO_BOUND : 0.0f;
  }
  pms_floatv costs = pms_cost_lanes(&in, &lanes, y, ca, cb, cc, bound);
  for (int l = 0; l < PMS_LANES; ++l) {
    if (lanes.active[l]) cost[y * width + lanes.x[l]] = costs[l];
  }
}

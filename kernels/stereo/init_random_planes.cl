/* A random plane for every pixel of one view, then its full cost
 * (reference: init_random_planes). The fourth plane component is written as 0, the
 * value the reference's PlaneField::resize leaves there. Each work item handles
 * PMS_LANES consecutive pixels of a row (pms_dense_lanes). */
#include "pms_lane_cost.h"

__kernel void init_random_planes(PMS_COST_KERNEL_ARGS, uint seed, uint iteration,
                                 float max_disparity, __global float* planes,
                                 __global float* cost) {
  PmsLanes lanes;
  int y;
  PmsCandidateBatch batch;
  if (!pms_dense_batch_begin(width, height, &lanes, &y, &batch)) return;
  for (int l = 0; l < PMS_LANES; ++l) {
    const int x = lanes.x[l];
    const int index = y * width + x;
    float abc[3];
    pms_random_plane(seed, (uint)view, (uint)index, iteration, x, y, max_disparity, abc);
    if (lanes.active[l]) {
      planes[4 * index] = abc[0];
      planes[4 * index + 1] = abc[1];
      planes[4 * index + 2] = abc[2];
      planes[4 * index + 3] = 0.0f;
    }
    pms_batch_set_unbounded(&batch, l, lanes.active[l], abc);
  }
  PmsCostInputs in = PMS_COST_INPUTS();
  pms_batch_store_costs(&batch, &in, &lanes, y, width, cost);
}

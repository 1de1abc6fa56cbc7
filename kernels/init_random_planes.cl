/* A random plane for every pixel of one view, then its full cost
 * (reference: init_random_planes). The fourth plane component is written as 0, the
 * value the reference's PlaneField::resize leaves there. Each work item handles
 * PMS_LANES consecutive pixels of a row (pms_dense_lanes). */
#include "pms_kernel_support.h"

__kernel void init_random_planes(PMS_COST_KERNEL_ARGS, uint seed, uint iteration,
                                 float max_disparity, __global float* planes,
                                 __global float* cost) {
  PmsLanes lanes;
  int y;
  if (!pms_dense_lanes(width, height, &lanes, &y)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  float ca[PMS_LANES], cb[PMS_LANES], cc[PMS_LANES], bound[PMS_LANES];
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

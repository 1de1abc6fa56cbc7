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
  PmsCandidateBatch batch;
  batch.any = 0;
  for (int l = 0; l < PMS_LANES; ++l) {
    float abc[3];
    pms_load_plane(planes, y * width + lanes.x[l], abc);
    pms_batch_set_unbounded(&batch, l, lanes.active[l], abc);
  }
  pms_batch_store_costs(&batch, &in, &lanes, y, width, cost);
}

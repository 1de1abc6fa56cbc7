/* Full cost of the plane every pixel already holds, after carrying planes from a
 * coarser level, or of the pixels where `unchanged` (may be NULL) is 0 after the filling
 * changed their planes (reference: evaluate_costs). Each work item handles PMS_LANES
 * consecutive pixels of a row (pms_dense_lanes); one whose pixels all kept their planes
 * costs nothing. */
#include "pms_lane_cost.h"

__kernel void evaluate_costs(PMS_COST_KERNEL_ARGS, const __global uchar* unchanged,
                             const __global float* planes, __global float* cost) {
  PmsLanes lanes;
  int y;
  PmsCandidateBatch batch;
  if (!pms_dense_batch_begin(width, height, &lanes, &y, &batch)) return;
  for (int l = 0; l < PMS_LANES; ++l) {
    const int index = y * width + lanes.x[l];
    float abc[3];
    pms_load_plane(planes, index, abc);
    const int changed = unchanged == 0 || !unchanged[index];
    pms_batch_set_unbounded(&batch, l, lanes.active[l] && changed, abc);
  }
  if (!batch.any) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  pms_batch_store_costs(&batch, &in, &lanes, y, width, cost);
}

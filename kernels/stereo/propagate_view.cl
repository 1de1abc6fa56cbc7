/* Pixels of one checkerboard parity try the plane of the pixel they match in the other
 * view, re-expressed in this view (reference: propagate_view). Each work item handles
 * PMS_LANES pixels of a row and evaluates them together: the whole parity when `list` is
 * NULL, otherwise the listed (unsure) pixels of list_unsure_pixels, the reference's
 * schedule.unsure_only. */
#include "pms_lane_cost.h"

__kernel void propagate_view(PMS_COST_KERNEL_ARGS, int parity,
                             const __global float* other_planes, PMS_SEARCH_STAGE_ARGS) {
  PmsBestPlane best[PMS_LANES];
  PmsLanes lanes;
  int y;
  if (!pms_search_begin(PMS_SEARCH_STAGE_INPUTS, &lanes, &y, best)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  PmsCandidateBatch batch;
  batch.any = 0;
  for (int l = 0; l < PMS_LANES; ++l) {
    float candidate[3] = {0.0f, 0.0f, 0.0f};
    const int x = lanes.x[l];
    int ok = lanes.active[l];
    if (ok) {
      float d = pms_plane_disparity(best[l].abc[0], best[l].abc[1], best[l].abc[2], (float)x,
                                    (float)y);
      float match_x = pms_floor_round((float)x + in.direction * d);
      ok = !(match_x < 0.0f || match_x > (float)(width - 1));
      if (ok) {
        float source[3];
        pms_load_plane(other_planes, y * width + (int)match_x, source);
        ok = pms_transfer_plane(source, 1 - view, candidate) &&
             !pms_best_same_as(&best[l], candidate);
      }
    }
    pms_batch_set(&batch, l, ok, candidate, &best[l]);
  }
  pms_batch_offer(&batch, &in, &lanes, y, best);
  pms_best_store_lanes(best, &lanes, y, width, planes, cost);
}

/* Pixels of one checkerboard colour try the planes of their PMS_SPATIAL_CANDIDATES
 * neighbours, which all have the other colour and so are not written by this launch
 * (reference: propagate_spatial); confident pixels only the first
 * confident_candidates. `confidence` may be NULL (coarsest level): then no pixel counts
 * as confident. Each work item handles PMS_LANES pixels of a row (pms_checker_lanes) and
 * evaluates their candidates together (pms_cost_lanes). */
#include "pms_kernel_support.h"

__kernel void propagate_spatial(PMS_COST_KERNEL_ARGS, int colour, float confident_threshold,
                                int confident_candidates, const __global float* confidence,
                                __global float* planes, __global float* cost) {
  PmsLanes lanes;
  int y;
  if (!pms_checker_lanes(width, height, colour, &lanes, &y)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  PmsBestPlane best[PMS_LANES];
  int confident[PMS_LANES];
  for (int l = 0; l < PMS_LANES; ++l) {
    const int index = y * width + lanes.x[l];
    best[l] = pms_best_load(planes, cost, index);
    confident[l] = confidence != 0 && confidence[index] >= confident_threshold;
  }
  for (int candidate = 0; candidate < PMS_SPATIAL_CANDIDATES; ++candidate) {
    int dx = 0;
    int dy = 0;
    pms_spatial_offset(candidate, &dx, &dy);
    int ny = y + dy;
    if (ny < 0 || ny >= height) continue;
    PmsCandidateBatch batch;
    batch.any = 0;
    for (int l = 0; l < PMS_LANES; ++l) {
      int nx = lanes.x[l] + dx;
      float neighbour[3] = {0.0f, 0.0f, 0.0f};
      int ok = lanes.active[l] && nx >= 0 && nx < width &&
               pms_spatial_candidate_tried(candidate, confident[l], confident_candidates);
      if (ok) {
        pms_load_plane(planes, ny * width + nx, neighbour);
        ok = !pms_best_same_as(&best[l], neighbour); /* its cost here is the one we hold */
      }
      pms_batch_set(&batch, l, ok, neighbour, &best[l]);
    }
    pms_batch_offer(&batch, &in, &lanes, y, best);
  }
  pms_best_store_lanes(best, &lanes, y, width, planes, cost);
}

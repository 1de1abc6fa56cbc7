/* Pixels of one checkerboard parity try the planes of their spatial candidates
 * first_candidate .. end_candidate - 1, which all have the other parity and so are not
 * written by this launch (reference: propagate_spatial, whose confidence rule the host
 * applies by launching the near candidates for every pixel of the parity, `list` NULL,
 * then the far ones for the unsure pixels of list_unsure_pixels). Each work item handles
 * PMS_LANES pixels of a row and evaluates their candidates together (pms_cost_lanes_group). */
#include "pms_lane_cost.h"

__kernel void propagate_spatial(PMS_COST_KERNEL_ARGS, int parity, int first_candidate,
                                int end_candidate, PMS_SEARCH_STAGE_ARGS) {
  PmsBestPlane best[PMS_LANES];
  PmsLanes lanes;
  int y;
  if (!pms_search_begin(PMS_SEARCH_STAGE_INPUTS, &lanes, &y, best)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  /* PMS_SPATIAL_GROUP candidates per window pass: their planes are the neighbours'
   * (of the other parity, unchanged by this launch), not derived from the best one, so
   * they can be costed together (pms_group_offer). */
  for (int group = first_candidate; group < end_candidate; group += PMS_SPATIAL_GROUP) {
    PmsCandidateBatch batches[PMS_SPATIAL_GROUP];
    for (int k = 0; k < PMS_SPATIAL_GROUP; ++k) {
      const int candidate = group + k;
      int dx = 0;
      int dy = 0;
      pms_spatial_offset(candidate, &dx, &dy);
      const int ny = y + dy;
      const int row_ok = candidate < end_candidate && ny >= 0 && ny < height;
      batches[k].any = 0;
      for (int l = 0; l < PMS_LANES; ++l) {
        int nx = lanes.x[l] + dx;
        float neighbour[3] = {0.0f, 0.0f, 0.0f};
        int ok = row_ok && lanes.active[l] && nx >= 0 && nx < width;
        if (ok) {
          pms_load_plane(planes, ny * width + nx, neighbour);
          ok = !pms_best_same_as(&best[l], neighbour); /* its cost here is the one we hold */
        }
        pms_batch_set(&batches[k], l, ok, neighbour, &best[l]);
      }
    }
    pms_group_offer(batches, PMS_SPATIAL_GROUP, &in, &lanes, y, best);
  }
  pms_best_store_lanes(best, &lanes, y, width, planes, cost);
}

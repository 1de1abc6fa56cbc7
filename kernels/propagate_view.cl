/* Pixels of one checkerboard colour try the plane of the pixel they match in the other
 * view, re-expressed in this view (reference: propagate_view). Each work item handles
 * PMS_LANES pixels of a row (pms_checker_lanes) and evaluates them together. */
#include "pms_kernel_support.h"

__kernel void propagate_view(PMS_COST_KERNEL_ARGS, int colour,
                             const __global float* other_planes, __global float* planes,
                             __global float* cost) {
  PmsLanes lanes;
  int y;
  if (!pms_checker_lanes(width, height, colour, &lanes, &y)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  PmsBestPlane best[PMS_LANES];
  float ca[PMS_LANES], cb[PMS_LANES], cc[PMS_LANES], bound[PMS_LANES];
  int tries[PMS_LANES];
  int any_try = 0;
  for (int l = 0; l < PMS_LANES; ++l) {
    const int x = lanes.x[l];
    best[l] = pms_best_load(planes, cost, y * width + x);
    float candidate[3] = {0.0f, 0.0f, 0.0f};
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
    tries[l] = ok;
    any_try |= ok;
    ca[l] = candidate[0];
    cb[l] = candidate[1];
    cc[l] = candidate[2];
    bound[l] = ok ? best[l].cost : 0.0f;
  }
  if (!any_try) return;
  pms_floatv costs = pms_cost_lanes(&in, &lanes, y, ca, cb, cc, bound);
  for (int l = 0; l < PMS_LANES; ++l) {
    if (!tries[l]) continue;
    float candidate[3] = {ca[l], cb[l], cc[l]};
    pms_best_offer(&best[l], candidate, costs[l]);
    pms_best_store(&best[l], planes, cost, y * width + lanes.x[l]);
  }
}

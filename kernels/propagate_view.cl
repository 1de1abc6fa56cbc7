/* Pixels of one checkerboard colour try the plane of the pixel they match in the other
 * view, re-expressed in this view (reference: propagate_view). */
#include "pms_kernel_support.h"

__kernel void propagate_view(PMS_COST_KERNEL_ARGS, int colour,
                             const __global float* other_planes, __global float* planes,
                             __global float* cost) {
  int x, y;
  if (!pms_checker_pixel(width, height, colour, &x, &y)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  int index = y * width + x;
  PmsBestPlane best = pms_best_load(planes, cost, index);
  float d = pms_plane_disparity(best.abc[0], best.abc[1], best.abc[2], (float)x, (float)y);
  float match_x = pms_floor_round((float)x + in.direction * d);
  if (match_x < 0.0f || match_x > (float)(width - 1)) return;
  float source[3];
  pms_load_plane(other_planes, y * width + (int)match_x, source);
  float candidate[3];
  if (!pms_transfer_plane(source, 1 - view, candidate)) return;
  if (pms_best_same_as(&best, candidate)) return;
  pms_best_offer(&best, candidate, pms_cost_at(&in, x, y, candidate, best.cost));
  pms_best_store(&best, planes, cost, index);
}

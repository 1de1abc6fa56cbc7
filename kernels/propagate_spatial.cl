/* Pixels of one checkerboard colour try the planes of their PMS_SPATIAL_CANDIDATES
 * neighbours, which all have the other colour and so are not written by this launch
 * (reference: propagate_spatial). */
#include "pms_kernel_support.h"

__kernel void propagate_spatial(PMS_COST_KERNEL_ARGS, int colour, __global float* planes,
                                __global float* cost) {
  int x, y;
  if (!pms_checker_pixel(width, height, colour, &x, &y)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  int index = y * width + x;
  PmsBestPlane best = pms_best_load(planes, cost, index);
  for (int candidate = 0; candidate < PMS_SPATIAL_CANDIDATES; ++candidate) {
    int dx = 0;
    int dy = 0;
    pms_spatial_offset(candidate, &dx, &dy);
    int nx = x + dx;
    int ny = y + dy;
    if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
    float neighbour[3];
    pms_load_plane(planes, ny * width + nx, neighbour);
    if (pms_best_same_as(&best, neighbour)) continue; /* its cost here is the one we hold */
    pms_best_offer(&best, neighbour, pms_cost_at(&in, x, y, neighbour, best.cost));
  }
  pms_best_store(&best, planes, cost, index);
}

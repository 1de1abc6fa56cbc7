/* Pixels of one checkerboard colour try random perturbations of their plane with
 * halving ranges (reference: refine_random). `confidence` may be NULL (coarsest level):
 * then no pixel counts as confident. */
#include "pms_kernel_support.h"

__kernel void refine_random(PMS_COST_KERNEL_ARGS, int colour, uint seed, uint iteration,
                            float max_disparity, float initial_range, float normal_range,
                            float min_range, float confident_threshold,
                            float confident_max_range, const __global float* confidence,
                            __global float* planes, __global float* cost) {
  int x, y;
  if (!pms_checker_pixel(width, height, colour, &x, &y)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  const int trials = pms_search_trial_count(initial_range, min_range);
  int index = y * width + x;
  int confident = confidence != 0 && confidence[index] >= confident_threshold;
  PmsBestPlane best = pms_best_load(planes, cost, index);
  float range = initial_range;
  float trial_normal_range = normal_range;
  for (int trial = 0; trial < trials;
       ++trial, range *= 0.5f, trial_normal_range *= 0.5f) {
    if (confident && range > confident_max_range) continue;
    float u[4];
    for (int c = 0; c < 4; ++c) {
      u[c] = pms_random_unit(seed, (uint)view, (uint)index, iteration,
                             pms_search_trial_key(trial, c));
    }
    float candidate[3];
    if (!pms_perturb_plane(best.abc, x, y, max_disparity, range, trial_normal_range, u[0],
                           u[1], u[2], u[3], candidate)) {
      continue;
    }
    pms_best_offer(&best, candidate, pms_cost_at(&in, x, y, candidate, best.cost));
  }
  pms_best_store(&best, planes, cost, index);
}

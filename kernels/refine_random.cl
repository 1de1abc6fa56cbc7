/* Pixels of one checkerboard colour try random perturbations of their plane with
 * halving ranges (reference: refine_random). `confidence` may be NULL (coarsest level):
 * then no pixel counts as confident. Each work item handles PMS_LANES pixels of a row
 * (pms_checker_lanes) and evaluates their trials together (pms_cost_lanes). */
#include "pms_kernel_support.h"

__kernel void refine_random(PMS_COST_KERNEL_ARGS, int colour, uint seed, uint iteration,
                            float max_disparity, float initial_range, float normal_range,
                            float min_range, float confident_threshold,
                            float confident_max_range, const __global float* confidence,
                            __global float* planes, __global float* cost) {
  PmsLanes lanes;
  int y;
  if (!pms_checker_lanes(width, height, colour, &lanes, &y)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  const int trials = pms_search_trial_count(initial_range, min_range);
  PmsBestPlane best[PMS_LANES];
  int confident[PMS_LANES];
  for (int l = 0; l < PMS_LANES; ++l) {
    int index = y * width + lanes.x[l];
    confident[l] = confidence != 0 && confidence[index] >= confident_threshold;
    best[l] = pms_best_load(planes, cost, index);
  }
  float range = initial_range;
  float trial_normal_range = normal_range;
  for (int trial = 0; trial < trials;
       ++trial, range *= 0.5f, trial_normal_range *= 0.5f) {
    PmsCandidateBatch batch;
    batch.any = 0;
    for (int l = 0; l < PMS_LANES; ++l) {
      const int x = lanes.x[l];
      float candidate[3] = {0.0f, 0.0f, 0.0f};
      int ok = lanes.active[l] && !(confident[l] && range > confident_max_range);
      if (ok) {
        uint index = (uint)(y * width + x);
        float u[4];
        for (int c = 0; c < 4; ++c) {
          u[c] = pms_random_unit(seed, (uint)view, index, iteration,
                                 pms_search_trial_key(trial, c));
        }
        ok = pms_perturb_plane(best[l].abc, x, y, max_disparity, range, trial_normal_range,
                               u[0], u[1], u[2], u[3], candidate);
      }
      pms_batch_set(&batch, l, ok, candidate, &best[l]);
    }
    pms_batch_offer(&batch, &in, &lanes, y, best);
  }
  pms_best_store_lanes(best, &lanes, y, width, planes, cost);
}

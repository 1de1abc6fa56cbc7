/* Pixels of one checkerboard parity try random perturbations of their plane with
 * halving ranges, trials first_trial .. end_trial - 1 of the schedule (reference:
 * refine_random, whose confidence rule the host applies by launching the wide trials for
 * the unsure pixels of list_unsure_pixels, then the others for every pixel of the
 * parity, `list` NULL). Each work item handles PMS_LANES pixels of a row and evaluates
 * their trials together (pms_batch_offer). */
#include "pms_lane_cost.h"

__kernel void refine_random(PMS_COST_KERNEL_ARGS, int parity, uint seed, uint iteration,
                            float max_disparity, float initial_range, float normal_range,
                            int first_trial, int end_trial, PMS_SEARCH_STAGE_ARGS) {
  PmsBestPlane best[PMS_LANES];
  PmsLanes lanes;
  int y;
  if (!pms_search_begin(PMS_SEARCH_STAGE_INPUTS, &lanes, &y, best)) return;
  PmsCostInputs in = PMS_COST_INPUTS();
  float range = initial_range;
  float trial_normal_range = normal_range;
  for (int trial = 0; trial < end_trial; ++trial, range *= 0.5f, trial_normal_range *= 0.5f) {
    if (trial < first_trial) continue; /* the ranges still halve, as in the reference */
    PmsCandidateBatch batch;
    batch.any = 0;
    for (int l = 0; l < PMS_LANES; ++l) {
      const int x = lanes.x[l];
      float candidate[3] = {0.0f, 0.0f, 0.0f};
      int ok = lanes.active[l];
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

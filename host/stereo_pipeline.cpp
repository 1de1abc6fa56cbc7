// The scheduler of the reference path: PPMS (or flat PMS) level by level, then the
// post-processing, as a short list of stage calls. The OpenCL path runs the same list
// with the same rules (host/pipeline_rules.h).
#include "host/stereo_pipeline.h"

#include <omp.h>

#include <chrono>
#include <utility>

#include "fallback/image_pyramid.h"
#include "fallback/patchmatch_reference.h"
#include "fallback/postprocess_reference.h"
#include "fallback/weight_table.h"
#include "host/pipeline_rules.h"

namespace flexsight {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The disparities of both views' planes, and from them each view's left/right
// confidence.
void confidence_from_planes(const PlaneField fields[2], int threads,
                            std::vector<float> disparity[2], std::vector<float> confidence[2]) {
  for (int view = 0; view < 2; ++view) disparity[view] = plane_disparities(fields[view], threads);
  for (int view = 0; view < 2; ++view) {
    confidence[view] = lr_confidence(disparity[view], disparity[1 - view], fields[view].width,
                                     fields[view].height, view, threads);
  }
}

// One PatchMatch iteration: each view, each checkerboard colour, the spatial and view
// propagation and the random search; `confidence` (null: none) steers them.
void run_iteration(const LevelInputs& in, const SearchSchedule& schedule, std::uint32_t key,
                   const std::vector<float>* confidence, PlaneField fields[2]) {
  for (int view = 0; view < 2; ++view) {
    const std::vector<float>* trusted = confidence ? &confidence[view] : nullptr;
    for (int colour = 0; colour < 2; ++colour) {
      propagate_spatial(in, view, colour, schedule, trusted, fields[view]);
      propagate_view(in, view, colour, schedule, trusted, fields[1 - view], fields[view]);
      refine_random(in, view, colour, key, schedule, trusted, fields[view]);
    }
  }
}

// Both views' pixels whose disparities fail the left/right check take the background
// plane of their row (fill_inconsistent); `consistent` gets each view's check, the
// pixels whose planes stayed.
void fill_both_views(const std::vector<float> disparity[2], const StereoParams& params,
                     int threads, PlaneField fields[2],
                     std::vector<std::uint8_t> consistent[2]) {
  for (int view = 0; view < 2; ++view) {
    consistent[view] =
        left_right_check(disparity[view], disparity[1 - view], fields[view].width,
                         fields[view].height, view, params.lr_tolerance, threads);
    fields[view].planes =
        fill_inconsistent(fields[view].planes, consistent[view], fields[view].width,
                          fields[view].height, params.fill_max_extrapolation, threads);
  }
}

}  // namespace

double StereoResult::total_seconds() const {
  double total = 0;
  for (const StageTiming& t : timings) total += t.seconds;
  return total;
}

StereoResult run_stereo(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                        const StereoParams& params, const ProgressCallback& progress) {
  validate_inputs(left_rgb8, right_rgb8, params);
  auto report = [&](const std::string& what) {
    if (progress) progress(what);
  };
  StereoResult result;
  const int threads = params.threads > 0 ? params.threads : omp_get_num_procs();
  const int levels = pipeline_level_count(params, left_rgb8.cols, left_rgb8.rows);

  auto start = Clock::now();
  const std::vector<ViewImage> pyramid[2] = {build_pyramid(left_rgb8, levels),
                                             build_pyramid(right_rgb8, levels)};
  const std::vector<float> weights =
      make_support_weight_table(params.gamma, params.gamma_distance);
  result.timings.push_back({"pyramid", seconds_since(start)});

  PlaneField fields[2];
  std::vector<float> confidence[2];  // of the current level, from the coarser one
  for (int level = levels - 1; level >= 0; --level) {
    start = Clock::now();
    LevelInputs in;
    in.views[PMS_VIEW_LEFT] = &pyramid[PMS_VIEW_LEFT][level];
    in.views[PMS_VIEW_RIGHT] = &pyramid[PMS_VIEW_RIGHT][level];
    const int width = in.views[0]->width;
    const int height = in.views[0]->height;
    const LevelPlan plan = plan_level(params, level, levels, width, height);
    in.weights = weights.data();
    in.cost = plan.cost;
    in.ndisp = plan.ndisp;
    in.seed = params.seed;
    in.threads = threads;

    // Start from random planes on the coarsest level, from the coarser level's planes
    // elsewhere.
    for (int view = 0; view < 2; ++view) {
      if (plan.coarsest) {
        init_random_planes(in, view, iteration_key(level, 0), fields[view]);
      } else {
        PlaneField coarse = std::move(fields[view]);
        fields[view].resize(width, height);
        carry_planes_to_finer(coarse, fields[view]);
        evaluate_costs(in, view, fields[view]);
        confidence[view] = upsample_nearest(confidence[view], coarse.width, coarse.height, width,
                                            height);
      }
    }

    const std::vector<float>* trusted = plan.use_confidence ? confidence : nullptr;
    for (int iteration = 1; iteration <= plan.iterations; ++iteration) {
      report(plan.iteration_label(iteration));
      run_iteration(in, plan.schedule, iteration_key(level, iteration), trusted, fields);
      // The next iteration trusts what this one made consistent.
      if (plan.refresh_confidence && iteration < plan.iterations) {
        std::vector<float> disparity[2];
        confidence_from_planes(fields, threads, disparity, confidence);
      }
    }

    // The pixels that fail the check start again from the background plane, steered by
    // the check (the confidence); their costs follow their new planes.
    if (plan.refill_iterations > 0) {
      std::vector<float> disparity[2];
      confidence_from_planes(fields, threads, disparity, confidence);
      std::vector<std::uint8_t> consistent[2];
      fill_both_views(disparity, params, threads, fields, consistent);
      // Only the filled pixels' planes changed.
      for (int view = 0; view < 2; ++view) {
        evaluate_costs(in, view, fields[view], &consistent[view]);
      }
      const std::vector<float>* refill_trusted =
          plan.refill_use_confidence ? confidence : nullptr;
      for (int iteration = 1; iteration <= plan.refill_iterations; ++iteration) {
        report(plan.refill_label(iteration));
        run_iteration(in, plan.refill_schedule, iteration_key(level, plan.iterations + iteration),
                      refill_trusted, fields);
      }
    }

    // The confidence that steers the next level's spatial and random search.
    if (plan.compute_confidence) {
      std::vector<float> disparity[2];
      confidence_from_planes(fields, threads, disparity, confidence);
      if (plan.fill_before_carry) {
        std::vector<std::uint8_t> consistent[2];
        fill_both_views(disparity, params, threads, fields, consistent);
      }
    }
    result.timings.push_back({plan.name, seconds_since(start)});
  }

  // Post-processing on the finest level.
  start = Clock::now();
  report("post-processing");
  const int width = left_rgb8.cols;
  const int height = left_rgb8.rows;
  const std::vector<float> raw_left = plane_disparities(fields[PMS_VIEW_LEFT], threads);
  const std::vector<float> raw_right = plane_disparities(fields[PMS_VIEW_RIGHT], threads);
  std::vector<std::uint8_t> consistent =
      left_right_check(raw_left, raw_right, width, height, PMS_VIEW_LEFT, params.lr_tolerance,
                       threads);
  if (params.raw_speckle_size > 0) {
    mask_and(consistent, large_segment_mask(raw_left, width, height, params.speckle_range,
                                            params.raw_speckle_size));
  }
  PlaneField filled;
  filled.width = width;
  filled.height = height;
  filled.planes = fill_inconsistent(fields[PMS_VIEW_LEFT].planes, consistent, width, height,
                                    params.fill_max_extrapolation, threads);
  const std::vector<float> median_weights = make_support_weight_table(params.median_gamma);
  std::vector<float> disparity = weighted_median_filled(
      plane_disparities(filled, threads), consistent, pyramid[PMS_VIEW_LEFT][0],
      median_weights.data(), params.median_window / 2, params.window_step,
      params.median_background_margin, threads);
  if (params.final_median_window > 1) {
    const std::vector<float> final_weights = make_support_weight_table(params.final_median_gamma);
    disparity = weighted_median_all(disparity, pyramid[PMS_VIEW_LEFT][0], final_weights.data(),
                                    params.final_median_window / 2, threads);
  }
  if (params.speckle_size > 0) {
    // Small segments are refilled like inconsistent pixels, from the pixels around them.
    const std::vector<std::uint8_t> kept = large_segment_mask(
        disparity, width, height, params.speckle_range, params.speckle_size);
    PlaneField flat;
    flat.width = width;
    flat.height = height;
    flat.planes = fill_inconsistent(flat_planes(disparity), kept, width, height, INFINITY,
                                    threads);
    disparity = weighted_median_filled(plane_disparities(flat, threads), kept,
                                       pyramid[PMS_VIEW_LEFT][0], median_weights.data(),
                                       params.median_window / 2, params.window_step,
                                       params.median_background_margin, threads);
  }
  clamp_to_disparity_range(disparity, params);
  result.timings.push_back({"post-processing", seconds_since(start)});

  result.disparity = to_mat(disparity, width, height, 1);
  result.raw_left = to_mat(raw_left, width, height, 1);
  result.raw_right = to_mat(raw_right, width, height, 1);
  result.planes_left = planes_to_mat(filled.planes, width, height);
  result.cost_left = to_mat(fields[PMS_VIEW_LEFT].cost, width, height, 1);
  return result;
}

}  // namespace flexsight

#pragma once
// The one schedule of the matcher, PPMS (pyramidal) and flat PMS, written as the
// algorithm reads: the pyramid; on each level from the coarsest, start (random planes,
// or the coarser level's planes carried), iterate (spatial propagation, view
// propagation and random refinement, per view and checkerboard parity), check and
// refill, and compute the confidence that steers the next level; then the
// post-processing. It runs over a stage set, which both paths implement with the same
// signatures:
//   - ReferenceStageSet (fallback/stereo/reference_stage_set.h): scalar C++ on vectors;
//   - OpenClStageSet (host/stereo/opencl_stage_set.h): the kernels on device buffers.
// So the order of the stages exists here only; what each level does (iterations,
// search ranges, keys) comes from pipeline_rules.h. Both paths give the same bytes
// because each stage does (tests/stereo/opencl/).
//
// A stage set S provides, besides the stages of OpenClStages (opencl_stages.h):
//   template <class T> using Array;  a pixel buffer (std::vector<T> or Buffer<T>)
//   View, Field, Level;              one view of a pyramid level, planes and costs of
//                                    a view, what a level's stages read
//   build_pyramid(rgb8, levels, view, census)   the view's pyramid, level 0 finest
//   array<T>(count, what), upload(values, what) buffers ("what" names them in errors)
//   field(width, height, view)                  planes and costs of a view
//   planes_field(width, height, planes)         planes without costs
//   prepare_level(level, left, right, weights, cost, ndisp, seed)
//   download(array) -> std::vector<float>; finish() waits for the device.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "host/stereo/texture_mask.h"
#include "fallback/stereo/weight_table.h"
#include "host/stereo/pipeline_rules.h"
#include "host/stereo/stereo_pipeline.h"

namespace flexsight {

template <class StageSet>
class PatchMatchSchedule {
 public:
  template <class T>
  using Array = typename StageSet::template Array<T>;
  using Floats = Array<float>;
  using Bytes = Array<std::uint8_t>;
  using View = typename StageSet::View;
  using Field = typename StageSet::Field;
  using Level = typename StageSet::Level;

  // `stage` (may be null) follows the stage that runs, for error messages.
  PatchMatchSchedule(StageSet& stages, const StereoParams& params,
                     const ProgressCallback& progress, std::string* stage = nullptr)
      : stages_(stages), params_(params), progress_(progress), stage_(stage) {}

  StereoResult run(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8) {
    validate_inputs(left_rgb8, right_rgb8, params_);
    if (params_.textureless_spread > 0) {
      textured_ = textured_pixel_mask(left_rgb8, params_.window, params_.textureless_spread);
    }
    enter("pyramid");
    const int levels = pipeline_level_count(params_, left_rgb8.cols, left_rgb8.rows);
    auto start = Clock::now();
    const PmsCensusShape census = census_shape(params_);
    pyramid_[PMS_VIEW_LEFT] = stages_.build_pyramid(left_rgb8, levels, PMS_VIEW_LEFT, census);
    pyramid_[PMS_VIEW_RIGHT] = stages_.build_pyramid(right_rgb8, levels, PMS_VIEW_RIGHT, census);
    weights_ = stages_.upload(make_support_weight_table(params_.gamma, params_.gamma_distance),
                              "weights");
    stages_.finish();
    result_.timings.push_back({"pyramid", seconds_since(start)});

    for (int level = levels - 1; level >= 0; --level) {
      start = Clock::now();
      const View& view = pyramid_[PMS_VIEW_LEFT][level];
      const LevelPlan plan = plan_level(params_, level, levels, view.width, view.height);
      enter(plan.name);
      run_level(plan);
      stages_.finish();
      result_.timings.push_back({plan.name, seconds_since(start)});
    }

    start = Clock::now();
    report("post-processing");
    post_process();
    result_.timings.push_back({"post-processing", seconds_since(start)});
    return std::move(result_);
  }

 private:
  using Clock = std::chrono::steady_clock;
  static double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  }

  void enter(const std::string& stage) {
    if (stage_) *stage_ = stage;
  }
  // A progress line: the stages of the iterations and the post-processing.
  void report(const std::string& what) {
    enter(what);
    if (progress_) progress_(what);
  }

  void run_level(const LevelPlan& plan) {
    Level in;  // only this level's inputs are alive at a time
    stages_.prepare_level(in, pyramid_[PMS_VIEW_LEFT][plan.level],
                          pyramid_[PMS_VIEW_RIGHT][plan.level], weights_, plan.cost, plan.ndisp,
                          params_.seed);
    start_level(in, plan);

    const Floats* trusted = plan.use_confidence ? confidence_ : nullptr;
    for (int iteration = 1; iteration <= plan.iterations; ++iteration) {
      report(plan.iteration_label(iteration));
      run_iteration(in, plan.schedule, iteration_key(plan.level, iteration), trusted);
      // The next iteration trusts what this one made consistent.
      if (plan.refresh_confidence && iteration < plan.iterations) {
        Floats disparity[2];
        confidence_from_planes(disparity);
      }
    }

    if (plan.refill_iterations > 0) check_and_refill(in, plan);

    // The confidence that steers the next level's spatial and random search.
    if (plan.compute_confidence) {
      Floats disparity[2];
      confidence_from_planes(disparity);
      if (plan.fill_before_carry) {
        Bytes consistent[2];
        fill_both_views(disparity, consistent);
      }
    }
  }

  // Random planes on the coarsest level; elsewhere the coarser level's planes and
  // confidence, carried to this level's pixels, and the planes' costs here.
  void start_level(const Level& in, const LevelPlan& plan) {
    const View& image = pyramid_[PMS_VIEW_LEFT][plan.level];
    const int width = image.width;
    const int height = image.height;
    const size_t pixels = static_cast<size_t>(width) * height;
    for (int view = 0; view < 2; ++view) {
      if (plan.coarsest) {
        fields_[view] = stages_.field(width, height, view);
        stages_.init_random_planes(in, view, iteration_key(plan.level, 0), fields_[view]);
        continue;
      }
      Field coarse = std::move(fields_[view]);
      fields_[view] = stages_.field(width, height, view);
      stages_.carry_planes_to_finer(coarse, fields_[view]);
      stages_.evaluate_costs(in, view, fields_[view], nullptr);
      Floats fine_confidence = stages_.template array<float>(pixels, "confidence");
      stages_.upsample_nearest(confidence_[view], coarse.width, coarse.height, fine_confidence,
                               width, height);
      confidence_[view] = std::move(fine_confidence);
    }
  }

  // One PatchMatch iteration: each view, each checkerboard parity, the spatial and view
  // propagation and the random search; `confidence` (null: none) steers them.
  void run_iteration(const Level& in, const SearchSchedule& schedule, std::uint32_t key,
                     const Floats* confidence) {
    for (int view = 0; view < 2; ++view) {
      const Floats* trusted = confidence ? &confidence[view] : nullptr;
      for (int parity = 0; parity < 2; ++parity) {
        stages_.propagate_spatial(in, view, parity, schedule, trusted, fields_[view]);
        stages_.propagate_view(in, view, parity, schedule, trusted, fields_[1 - view],
                               fields_[view]);
        stages_.refine_random(in, view, parity, key, schedule, trusted, fields_[view]);
      }
    }
  }

  // The pixels that fail the left/right check start again from the background plane,
  // steered by the check (the confidence); their costs follow their new planes.
  void check_and_refill(const Level& in, const LevelPlan& plan) {
    Floats disparity[2];
    confidence_from_planes(disparity);
    Bytes consistent[2];
    fill_both_views(disparity, consistent);
    // Only the filled pixels' planes changed.
    for (int view = 0; view < 2; ++view) {
      stages_.evaluate_costs(in, view, fields_[view], &consistent[view]);
    }
    const Floats* trusted = plan.refill_use_confidence ? confidence_ : nullptr;
    for (int iteration = 1; iteration <= plan.refill_iterations; ++iteration) {
      report(plan.refill_label(iteration));
      run_iteration(in, plan.refill_schedule,
                    iteration_key(plan.level, plan.iterations + iteration), trusted);
    }
  }

  // The disparities of both views' planes into `disparity`, and from them each view's
  // left/right confidence (its buffer reused when it has the level's size).
  void confidence_from_planes(Floats disparity[2]) {
    const int width = fields_[0].width;
    const int height = fields_[0].height;
    const size_t pixels = static_cast<size_t>(width) * height;
    for (int view = 0; view < 2; ++view) {
      disparity[view] = stages_.template array<float>(pixels, kDisparityNames[view]);
      stages_.plane_disparities(fields_[view], disparity[view]);
    }
    for (int view = 0; view < 2; ++view) {
      if (confidence_[view].size() != pixels) {
        confidence_[view] = stages_.template array<float>(pixels, "confidence");
      }
      stages_.lr_confidence(disparity[view], disparity[1 - view], width, height, view,
                            confidence_[view]);
    }
  }

  // Both views' pixels that fail the left/right check take the background plane of
  // their row (fill_inconsistent); `consistent` gets each view's check.
  void fill_both_views(const Floats disparity[2], Bytes consistent[2]) {
    const int width = fields_[0].width;
    const int height = fields_[0].height;
    const size_t pixels = static_cast<size_t>(width) * height;
    for (int view = 0; view < 2; ++view) {
      consistent[view] = stages_.template array<std::uint8_t>(pixels, "consistent");
      stages_.left_right_check(disparity[view], disparity[1 - view], width, height, view,
                               params_.lr_tolerance, consistent[view]);
      Floats filled = stages_.template array<float>(4 * pixels, "filled planes");
      stages_.fill_inconsistent(fields_[view].planes, consistent[view], width, height,
                                params_.fill_max_extrapolation, filled);
      fields_[view].planes = std::move(filled);
    }
  }

  void post_process();
  // Small segments of the final disparity refilled like inconsistent pixels, from the
  // pixels around them; returns the refilled disparity.
  Floats refill_small_segments(const Floats& disparity, const Floats& median_weights);

  static constexpr const char* kDisparityNames[2] = {"disparity (left)", "disparity (right)"};

  StageSet& stages_;
  const StereoParams& params_;
  const ProgressCallback& progress_;
  std::string* stage_;
  StereoResult result_;
  std::vector<View> pyramid_[2];
  Floats weights_;
  Field fields_[2];
  Floats confidence_[2];  // of the current level, from the coarser one
  std::vector<std::uint8_t> textured_;  // textured_pixel_mask of the left image (or empty)
};

// Post-processing on the finest level (Bleyer et al. 2011, Sec. 3.3, and the
// departures of docs/stereo.md): left/right check, fill of the inconsistent pixels
// with the background plane, a weighted median over the filled pixels, a small
// weighted median over all, the refill of small segments, the clamp. Buffers no longer
// needed are written over, which keeps the device's peak memory down.
template <class StageSet>
void PatchMatchSchedule<StageSet>::post_process() {
  const View& image = pyramid_[PMS_VIEW_LEFT][0];
  const int width = image.width;
  const int height = image.height;
  const size_t pixels = static_cast<size_t>(width) * height;
  Floats raw[2] = {stages_.template array<float>(pixels, "raw disparity (left)"),
                   stages_.template array<float>(pixels, "raw disparity (right)")};
  for (int view = 0; view < 2; ++view) stages_.plane_disparities(fields_[view], raw[view]);
  Bytes consistent = stages_.template array<std::uint8_t>(pixels, "consistent");
  stages_.left_right_check(raw[PMS_VIEW_LEFT], raw[PMS_VIEW_RIGHT], width, height,
                           PMS_VIEW_LEFT, params_.lr_tolerance, consistent);
  if (params_.raw_speckle_size > 0) {
    Bytes large = stages_.template array<std::uint8_t>(pixels, "large raw segments");
    stages_.large_segment_mask(raw[PMS_VIEW_LEFT], width, height, params_.speckle_range,
                               params_.speckle_slopes,
                               params_.raw_speckle_size, large);
    stages_.mask_and(large, width, height, consistent);
  }
  if (!textured_.empty()) {
    // A window without texture matches about anywhere, in both views alike, so its
    // consistency means nothing: it is filled from its textured neighbours' planes.
    const Bytes textured = stages_.upload(textured_, "textured pixels");
    stages_.mask_and(textured, width, height, consistent);
  }
  Floats filled_planes = stages_.template array<float>(4 * pixels, "filled planes");
  stages_.fill_inconsistent(fields_[PMS_VIEW_LEFT].planes, consistent, width, height,
                            params_.fill_max_extrapolation, filled_planes);
  const Field filled = stages_.planes_field(width, height, std::move(filled_planes));
  Floats filled_disparity = stages_.template array<float>(pixels, "filled disparity");
  stages_.plane_disparities(filled, filled_disparity);
  const Floats median_weights =
      stages_.upload(make_support_weight_table(params_.median_gamma), "median weights");
  Floats filtered = stages_.template array<float>(pixels, "filtered disparity");
  stages_.weighted_median_filled(filled_disparity, consistent, image, median_weights,
                                 params_.median_window / 2, params_.window_step,
                                 params_.median_background_margin, filtered);
  const Floats* final_disparity = &filtered;
  if (params_.final_median_window > 1) {
    const Floats final_weights = stages_.upload(
        make_support_weight_table(params_.final_median_gamma), "final median weights");
    // The filled disparities are no longer needed: the second median writes over them.
    stages_.weighted_median_all(filtered, image, final_weights, params_.final_median_window / 2,
                                filled_disparity);
    final_disparity = &filled_disparity;
  }
  Floats refilled;
  if (params_.speckle_size > 0) {
    refilled = refill_small_segments(*final_disparity, median_weights);
    final_disparity = &refilled;
  }

  std::vector<float> disparity = stages_.download(*final_disparity);
  clamp_to_disparity_range(disparity, params_);
  result_.disparity = to_mat(disparity, width, height, 1);
  result_.raw_left = to_mat(stages_.download(raw[PMS_VIEW_LEFT]), width, height, 1);
  result_.raw_right = to_mat(stages_.download(raw[PMS_VIEW_RIGHT]), width, height, 1);
  result_.planes_left = planes_to_mat(stages_.download(filled.planes), width, height);
  result_.cost_left = to_mat(stages_.download(fields_[PMS_VIEW_LEFT].cost), width, height, 1);
}

template <class StageSet>
typename PatchMatchSchedule<StageSet>::Floats
PatchMatchSchedule<StageSet>::refill_small_segments(const Floats& disparity,
                                                    const Floats& median_weights) {
  const View& image = pyramid_[PMS_VIEW_LEFT][0];
  const int width = image.width;
  const int height = image.height;
  const size_t pixels = static_cast<size_t>(width) * height;
  Bytes kept = stages_.template array<std::uint8_t>(pixels, "large segments");
  stages_.large_segment_mask(disparity, width, height, params_.speckle_range,
                             params_.speckle_slopes,
                             params_.speckle_size, kept);
  Floats flat = stages_.template array<float>(4 * pixels, "flat planes");
  stages_.flat_planes(disparity, width, height, flat);
  // The right view's planes are no longer needed: the refill's planes go there.
  Field& flat_filled = fields_[PMS_VIEW_RIGHT];
  stages_.fill_inconsistent(flat, kept, width, height, INFINITY, flat_filled.planes);
  flat = Floats();
  Floats flat_disparity = stages_.template array<float>(pixels, "refill's filled disparity");
  stages_.plane_disparities(flat_filled, flat_disparity);
  Floats refilled = stages_.template array<float>(pixels, "refilled disparity");
  stages_.weighted_median_filled(flat_disparity, kept, image, median_weights,
                                 params_.median_window / 2, params_.window_step,
                                 params_.median_background_margin, refilled);
  return refilled;
}

}  // namespace flexsight

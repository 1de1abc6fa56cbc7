#pragma once
// The rules of the matcher's schedule that decide the bytes of the result: input
// validation, the pyramid's levels, each level's disparity range, iterations, random
// search and use of confidence, the random-generator keys and the final clamp. Both
// schedulers, the reference one (host/stereo/stereo_pipeline.cpp) and the OpenCL one
// (host/stereo/opencl_matcher.cpp), take them from here, so they cannot drift apart.
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "fallback/stereo/patchmatch_reference.h"
#include "host/stereo/stereo_params.h"

namespace flexsight {

// Throws InputError when params.check() fails, an image is empty or not RGB8, the two
// differ in size, or ndisp exceeds the image width.
void validate_inputs(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                     const StereoParams& params);

// Pyramid levels of a run on a width x height pair: 1 for flat PMS.
int pipeline_level_count(const StereoParams& params, int width, int height);

// Disparity range of a level: ndisp halves (rounding up) with each level, at least 2.
int level_ndisp(int ndisp, int level);

// Random-generator iteration key: unique per (level, iteration); 0 is the initialisation.
std::uint32_t iteration_key(int level, int iteration);

// What one pyramid level does, from the coarsest (levels - 1) down to 0.
struct LevelPlan {
  int level = 0;
  // Starts from random planes; otherwise from the coarser level's planes (carried).
  bool coarsest = false;
  int ndisp = 0;      // disparity range of the level
  PmsCostParams cost{};
  int iterations = 0;  // PatchMatch iterations (both views, both parities each)
  SearchSchedule schedule;
  // The spatial and random search are steered by the coarser level's left/right
  // confidence.
  bool use_confidence = false;
  // After each iteration but the last, the confidence is recomputed from this level's
  // planes (StereoParams::refresh_confidence).
  bool refresh_confidence = false;
  // Then (finest level only) both views' pixels that fail the left/right check take the
  // background plane and this many more iterations run, steered by that check
  // (StereoParams::refill_iterations).
  int refill_iterations = 0;
  // The search settings of those iterations: the level's, but with
  // StereoParams::refill_unsure_only the confident pixels sit them out.
  SearchSchedule refill_schedule;
  // Those iterations are steered by the check's confidence (PPMS's finer levels, or any
  // level whose refill is for the unsure pixels only).
  bool refill_use_confidence = false;
  // The level computes the confidence that steers the next finer level.
  bool compute_confidence = false;
  // Then its inconsistent pixels take the background plane (fill_inconsistent) before
  // the planes are carried.
  bool fill_before_carry = false;
  // "level 2 (160x120)": the stage name of the timings and progress lines.
  std::string name;

  // Progress line of an iteration: "level 2 (160x120), iteration 1/3".
  std::string iteration_label(int iteration) const;
  // "level 0 (640x480), after the check-and-fill, iteration 1/1".
  std::string refill_label(int iteration) const;
};

// The census neighbourhood of StereoParams::census_rows / cols / row_length.
PmsCensusShape census_shape(const StereoParams& params);

// `width` x `height`: the size of the level (for its name).
LevelPlan plan_level(const StereoParams& params, int level, int levels, int width, int height);

// The post-processed disparity clamped to [0, ndisp - 1], in place.
void clamp_to_disparity_range(std::vector<float>& disparity, const StereoParams& params);

// `values` (width * height * channels floats) as a CV_32FC(channels).
cv::Mat to_mat(const std::vector<float>& values, int width, int height, int channels);

// Planes (4 floats per pixel) as a CV_32FC3 of (a, b, c).
cv::Mat planes_to_mat(const std::vector<float>& planes, int width, int height);

}  // namespace flexsight

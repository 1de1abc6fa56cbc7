#include "host/stereo/pipeline_rules.h"

#include <algorithm>

#include "fallback/stereo/image_pyramid.h"
#include "host/io/input_error.h"

namespace flexsight {

void validate_inputs(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                     const StereoParams& params) {
  params.check();
  if (left_rgb8.empty() || right_rgb8.empty()) {
    throw InputError("stereo pair", "an image is empty");
  }
  if (left_rgb8.type() != CV_8UC3 || right_rgb8.type() != CV_8UC3) {
    throw InputError("stereo pair", "images must be 8-bit RGB");
  }
  if (left_rgb8.size() != right_rgb8.size()) {
    throw InputError("stereo pair", "left and right images differ in size");
  }
  if (params.ndisp > left_rgb8.cols) {
    throw InputError("parameter --ndisp", "is " + std::to_string(params.ndisp) +
                                              ", wider than the image (" +
                                              std::to_string(left_rgb8.cols) + " px)");
  }
}

int pipeline_level_count(const StereoParams& params, int width, int height) {
  return params.method == StereoMethod::PMS
             ? 1
             : pyramid_level_count(width, height, params.coarsest_width);
}

int level_ndisp(int ndisp, int level) {
  int n = ndisp;
  for (int i = 0; i < level; ++i) n = (n + 1) / 2;
  return std::max(n, 2);
}

std::uint32_t iteration_key(int level, int iteration) {
  return static_cast<std::uint32_t>(level * 64 + iteration);
}

std::string LevelPlan::iteration_label(int iteration) const {
  return name + ", iteration " + std::to_string(iteration) + "/" + std::to_string(iterations);
}

std::string LevelPlan::refill_label(int iteration) const {
  return name + ", after the check-and-fill, iteration " + std::to_string(iteration) + "/" +
         std::to_string(refill_iterations);
}

PmsCensusShape census_shape(const StereoParams& params) {
  return {params.census_rows / 2, params.census_cols / 2, params.census_row_length / 2};
}

LevelPlan plan_level(const StereoParams& params, int level, int levels, int width, int height) {
  LevelPlan plan;
  plan.level = level;
  plan.coarsest = level == levels - 1;
  plan.ndisp = level_ndisp(params.ndisp, level);
  const int window_rows = params.window_rows > 0 ? params.window_rows : params.window;
  plan.cost = {params.window / 2, window_rows / 2, params.window_step, params.alpha,
               1.0f - params.alpha,
               params.tau_color, params.tau_gradient, params.census_weight, params.census_cap};
  if (params.method == StereoMethod::PMS) {
    plan.iterations = params.iterations;
  } else {
    plan.iterations = plan.coarsest ? params.iterations_coarsest : params.iterations_fine;
    // Below the coarsest level the planes come carried from the level above and only
    // need refining: a sparser window there costs no accuracy beyond the seed spread
    // and most of the time goes there (StereoParams::window_step_fine).
    if (!plan.coarsest) plan.cost.step = params.window_step_fine;
    // The finest level may take its own (StereoParams::window_step_finest).
    if (!plan.coarsest && level == 0) {
      if (params.window_step_finest > 0) plan.cost.step = params.window_step_finest;
      if (params.iterations_finest > 0) plan.iterations = params.iterations_finest;
    }
  }

  // Half the level's disparity range at first; below the coarsest level the carried
  // planes are already close, so the search starts at most at fine_search_range.
  plan.schedule.initial_range = 0.5f * static_cast<float>(plan.ndisp);
  if (!plan.coarsest) {
    plan.schedule.initial_range = std::min(plan.schedule.initial_range, params.fine_search_range);
  }
  plan.schedule.normal_range = params.max_normal_delta;
  plan.schedule.min_range = params.min_search_range;
  plan.schedule.confident_threshold = params.confident_threshold;
  plan.schedule.confident_max_range = params.confident_max_range;
  plan.schedule.confident_spatial_candidates = params.confident_spatial_candidates;

  plan.use_confidence = !plan.coarsest;
  plan.refresh_confidence = plan.use_confidence && params.refresh_confidence;
  plan.compute_confidence = level > 0;
  plan.fill_before_carry = level > 0 && params.fill_coarse;
  plan.refill_iterations = level == 0 ? params.refill_iterations : 0;
  plan.refill_schedule = plan.schedule;
  plan.refill_schedule.unsure_only = params.refill_unsure_only;
  plan.refill_use_confidence = plan.use_confidence || plan.refill_schedule.unsure_only;
  plan.name = "level " + std::to_string(level) + " (" + std::to_string(width) + "x" +
              std::to_string(height) + ")";
  return plan;
}

void clamp_to_disparity_range(std::vector<float>& disparity, const StereoParams& params) {
  const float max_disparity = static_cast<float>(params.ndisp - 1);
  for (float& d : disparity) d = std::min(std::max(d, 0.0f), max_disparity);
}

cv::Mat to_mat(const std::vector<float>& values, int width, int height, int channels) {
  cv::Mat mat(height, width, CV_32FC(channels));
  std::copy(values.begin(), values.end(), mat.ptr<float>());
  return mat;
}

cv::Mat planes_to_mat(const std::vector<float>& planes, int width, int height) {
  cv::Mat mat(height, width, CV_32FC3);
  for (int i = 0; i < width * height; ++i) {
    mat.ptr<cv::Vec3f>()[i] = cv::Vec3f(planes[4 * i], planes[4 * i + 1], planes[4 * i + 2]);
  }
  return mat;
}

}  // namespace flexsight

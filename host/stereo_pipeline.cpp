// The scheduler of the reference path: PPMS (or flat PMS) level by level, then the
// post-processing, as a short list of stage calls. The OpenCL path runs the same list.
#include "host/stereo_pipeline.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "fallback/image_pyramid.h"
#include "fallback/patchmatch_reference.h"
#include "fallback/postprocess_reference.h"
#include "fallback/weight_table.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

cv::Mat to_mat(const std::vector<float>& values, int width, int height, int channels) {
  cv::Mat mat(height, width, CV_32FC(channels));
  std::copy(values.begin(), values.end(), mat.ptr<float>());
  return mat;
}

// Planes (4 floats per pixel) as a CV_32FC3 of (a, b, c).
cv::Mat planes_to_mat(const std::vector<float>& planes, int width, int height) {
  cv::Mat mat(height, width, CV_32FC3);
  for (int i = 0; i < width * height; ++i) {
    mat.ptr<cv::Vec3f>()[i] = cv::Vec3f(planes[4 * i], planes[4 * i + 1], planes[4 * i + 2]);
  }
  return mat;
}

// Disparity range of a level: ndisp halves (rounding up) with each level.
int level_ndisp(int ndisp, int level) {
  int n = ndisp;
  for (int i = 0; i < level; ++i) n = (n + 1) / 2;
  return std::max(n, 2);
}

// Random-generator iteration key: unique per (level, iteration); 0 is the initialisation.
std::uint32_t iteration_key(int level, int iteration) {
  return static_cast<std::uint32_t>(level * 64 + iteration);
}

void validate_inputs(const cv::Mat& left, const cv::Mat& right, const StereoParams& params) {
  params.check();
  if (left.empty() || right.empty()) throw InputError("stereo pair", "an image is empty");
  if (left.type() != CV_8UC3 || right.type() != CV_8UC3) {
    throw InputError("stereo pair", "images must be 8-bit RGB");
  }
  if (left.size() != right.size()) {
    throw InputError("stereo pair", "left and right images differ in size");
  }
  if (params.ndisp > left.cols) {
    throw InputError("parameter --ndisp", "is " + std::to_string(params.ndisp) +
                                              ", wider than the image (" +
                                              std::to_string(left.cols) + " px)");
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
  const int levels = params.method == StereoMethod::PMS
                         ? 1
                         : pyramid_level_count(left_rgb8.cols, left_rgb8.rows, params.coarsest_width);

  auto start = Clock::now();
  const std::vector<ViewImage> pyramid[2] = {build_pyramid(left_rgb8, levels),
                                             build_pyramid(right_rgb8, levels)};
  const std::vector<float> weights = make_support_weight_table(params.gamma);
  result.timings.push_back({"pyramid", seconds_since(start)});

  PlaneField fields[2];
  std::vector<float> confidence[2];  // of the current level, from the coarser one
  for (int level = levels - 1; level >= 0; --level) {
    start = Clock::now();
    const bool coarsest = level == levels - 1;
    LevelInputs in;
    in.views[PMS_VIEW_LEFT] = &pyramid[PMS_VIEW_LEFT][level];
    in.views[PMS_VIEW_RIGHT] = &pyramid[PMS_VIEW_RIGHT][level];
    in.weights = weights.data();
    in.cost = {params.window / 2, params.window_step, params.alpha, 1.0f - params.alpha,
               params.tau_color, params.tau_gradient};
    in.ndisp = level_ndisp(params.ndisp, level);
    in.seed = params.seed;
    in.threads = threads;
    const int width = in.views[0]->width;
    const int height = in.views[0]->height;
    const std::string level_name = "level " + std::to_string(level) + " (" +
                                   std::to_string(width) + "x" + std::to_string(height) + ")";

    // Start from random planes on the coarsest level, from the coarser level's planes
    // elsewhere.
    for (int view = 0; view < 2; ++view) {
      if (coarsest) {
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

    SearchSchedule schedule;
    schedule.initial_range = 0.5f * static_cast<float>(in.ndisp);
    if (!coarsest) schedule.initial_range = std::min(schedule.initial_range, params.fine_search_range);
    schedule.normal_range = params.max_normal_delta;
    schedule.min_range = params.min_search_range;
    schedule.confident_threshold = params.confident_threshold;
    schedule.confident_max_range = params.confident_max_range;

    const int iterations = coarsest ? params.iterations : params.iterations_fine;
    for (int iteration = 1; iteration <= iterations; ++iteration) {
      report(level_name + ", iteration " + std::to_string(iteration) + "/" +
             std::to_string(iterations));
      for (int view = 0; view < 2; ++view) {
        const std::vector<float>* trusted = coarsest ? nullptr : &confidence[view];
        for (int colour = 0; colour < 2; ++colour) {
          propagate_spatial(in, view, colour, fields[view]);
          propagate_view(in, view, colour, fields[1 - view], fields[view]);
          refine_random(in, view, colour, iteration_key(level, iteration), schedule, trusted,
                        fields[view]);
        }
      }
    }

    // The confidence that steers the next level's random search.
    if (level > 0) {
      const std::vector<float> disparity[2] = {plane_disparities(fields[0], threads),
                                               plane_disparities(fields[1], threads)};
      for (int view = 0; view < 2; ++view) {
        confidence[view] =
            lr_confidence(disparity[view], disparity[1 - view], width, height, view, threads);
      }
    }
    result.timings.push_back({level_name, seconds_since(start)});
  }

  // Post-processing on the finest level.
  start = Clock::now();
  report("post-processing");
  const int width = left_rgb8.cols;
  const int height = left_rgb8.rows;
  const std::vector<float> raw_left = plane_disparities(fields[PMS_VIEW_LEFT], threads);
  const std::vector<float> raw_right = plane_disparities(fields[PMS_VIEW_RIGHT], threads);
  const std::vector<std::uint8_t> consistent =
      left_right_check(raw_left, raw_right, width, height, params.lr_tolerance, threads);
  PlaneField filled;
  filled.width = width;
  filled.height = height;
  filled.planes = fill_inconsistent(fields[PMS_VIEW_LEFT].planes, consistent, width, height, threads);
  const std::vector<float> median_weights = make_support_weight_table(params.median_gamma);
  std::vector<float> disparity = weighted_median_filled(
      plane_disparities(filled, threads), consistent, pyramid[PMS_VIEW_LEFT][0],
      median_weights.data(), params.median_window / 2, params.window_step, threads);
  const float max_disparity = static_cast<float>(params.ndisp - 1);
  for (float& d : disparity) d = std::min(std::max(d, 0.0f), max_disparity);
  result.timings.push_back({"post-processing", seconds_since(start)});

  result.disparity = to_mat(disparity, width, height, 1);
  result.raw_left = to_mat(raw_left, width, height, 1);
  result.raw_right = to_mat(raw_right, width, height, 1);
  result.planes_left = planes_to_mat(filled.planes, width, height);
  return result;
}

}  // namespace flexsight

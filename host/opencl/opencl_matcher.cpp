// The OpenCL scheduler: host/stereo_pipeline.cpp's stage list, stage for stage, with
// device buffers in place of the reference's vectors. The rules that decide the bytes
// (validation, levels, iterations, search schedule, keys, clamp) come from
// host/pipeline_rules.h for both; keep the stage order in step too: the pipeline tests
// compare the results byte for byte.
#include "host/opencl/opencl_matcher.h"

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>

#include "fallback/image_pyramid.h"
#include "fallback/weight_table.h"
#include "host/io/input_error.h"
#include "host/opencl/cl_program.h"
#include "host/opencl/opencl_stages.h"
#include "host/pipeline_rules.h"

namespace flexsight::opencl {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

DeviceView make_view(Context& context, int width, int height, const char* name) {
  const size_t pixels = static_cast<size_t>(width) * height;
  return {width, height, Buffer<float>(context, 4 * pixels, std::string(name) + " colour"),
          Buffer<float>(context, 2 * pixels, std::string(name) + " gradient")};
}

DeviceField make_field(Context& context, int width, int height, const char* name) {
  const size_t pixels = static_cast<size_t>(width) * height;
  return {width, height, Buffer<float>(context, 4 * pixels, std::string(name) + " planes"),
          Buffer<float>(context, pixels, std::string(name) + " cost")};
}

// build_pyramid on the device: level 0 from the host colour, then downsample.
std::vector<DeviceView> build_device_pyramid(OpenClStages& stages, const cv::Mat& rgb8,
                                             int levels, const char* name) {
  std::vector<DeviceView> pyramid;
  pyramid.reserve(levels);
  pyramid.push_back(make_view(stages.context(), rgb8.cols, rgb8.rows, name));
  pyramid.back().color.write(view_color(rgb8));
  stages.compute_gradient(pyramid.back());
  for (int level = 1; level < levels; ++level) {
    const DeviceView& fine = pyramid.back();
    DeviceView coarse =
        make_view(stages.context(), (fine.width + 1) / 2, (fine.height + 1) / 2, name);
    stages.downsample_color(fine, coarse);
    stages.compute_gradient(coarse);
    pyramid.push_back(std::move(coarse));
  }
  return pyramid;
}

const char* const kViewNames[2] = {"left", "right"};

// The disparities of both views' planes into `disparity`, and from them each view's
// left/right confidence into `confidence` (reused when it has the fields' size).
void confidence_from_planes(OpenClStages& stages, const DeviceField fields[2],
                            Buffer<float> disparity[2], Buffer<float> confidence[2]) {
  const int width = fields[0].width;
  const int height = fields[0].height;
  const size_t pixels = fields[0].pixels();
  for (int view = 0; view < 2; ++view) {
    disparity[view] = Buffer<float>(stages.context(), pixels,
                                    std::string("disparity (") + kViewNames[view] + ")");
    stages.plane_disparities(fields[view], disparity[view]);
  }
  for (int view = 0; view < 2; ++view) {
    if (confidence[view].size() != pixels) {
      confidence[view] = Buffer<float>(stages.context(), pixels, "confidence");
    }
    stages.lr_confidence(disparity[view], disparity[1 - view], width, height, view,
                         confidence[view]);
  }
}

// One PatchMatch iteration (stereo_pipeline.cpp's run_iteration); `confidence` (null:
// none) steers it.
void run_iteration(OpenClStages& stages, const DeviceLevel& in, const SearchSchedule& schedule,
                   std::uint32_t key, const Buffer<float>* confidence, DeviceField fields[2]) {
  for (int view = 0; view < 2; ++view) {
    const Buffer<float>* trusted = confidence ? &confidence[view] : nullptr;
    for (int colour = 0; colour < 2; ++colour) {
      stages.propagate_spatial(in, view, colour, schedule, trusted, fields[view]);
      stages.propagate_view(in, view, colour, schedule, trusted, fields[1 - view],
                            fields[view]);
      stages.refine_random(in, view, colour, key, schedule, trusted, fields[view]);
    }
  }
}

// Both views' pixels that fail the left/right check take the background plane
// (stereo_pipeline.cpp's fill_both_views); `consistent` gets each view's check.
void fill_both_views(OpenClStages& stages, const Buffer<float> disparity[2],
                     const StereoParams& params, DeviceField fields[2],
                     Buffer<std::uint8_t> consistent[2]) {
  const int width = fields[0].width;
  const int height = fields[0].height;
  const size_t pixels = fields[0].pixels();
  for (int view = 0; view < 2; ++view) {
    consistent[view] = Buffer<std::uint8_t>(stages.context(), pixels, "consistent");
    stages.left_right_check(disparity[view], disparity[1 - view], width, height, view,
                            params.lr_tolerance, consistent[view]);
    Buffer<float> filled(stages.context(), 4 * pixels, "filled planes");
    stages.fill_inconsistent(fields[view].planes, consistent[view], width, height,
                             params.fill_max_extrapolation, filled);
    fields[view].planes = std::move(filled);
  }
}

// Pixels per work item of the cost kernels: FLEXSIGHT_CL_LANES when set (1 for a GPU,
// see OpenClStages::kDefaultCostLanes), else the default, which suits CPU drivers.
int cost_lanes_from_environment() {
  const char* text = std::getenv("FLEXSIGHT_CL_LANES");
  if (text == nullptr || *text == '\0') return OpenClStages::kDefaultCostLanes;
  char* end = nullptr;
  const long lanes = std::strtol(text, &end, 10);
  if (*end != '\0' || lanes < 1 || lanes > 16 ||
      !OpenClStages::supports_cost_lanes(static_cast<int>(lanes))) {
    throw InputError("environment variable FLEXSIGHT_CL_LANES",
                     std::string("must be 1, 4, 8 or 16, got '") + text + "'");
  }
  return static_cast<int>(lanes);
}

}  // namespace

struct OpenClMatcher::State {
  Context context;
  KernelProfiler profiler;
  OpenClStages stages;
  State(const DeviceInfo& device, bool profile, const std::string& build_options)
      : context(device, build_options),
        stages(context, profile ? &profiler : nullptr, cost_lanes_from_environment()) {}
};

bool opencl_available(std::string* why) {
  try {
    if (!enumerate_devices().empty()) return true;
    if (why) *why = "no OpenCL platform or device is installed";
  } catch (const OpenClError& error) {
    if (why) *why = error.what();
  }
  return false;
}

std::vector<std::string> list_opencl_devices() {
  std::vector<std::string> lines;
  for (const DeviceInfo& device : enumerate_devices()) lines.push_back(device.description());
  return lines;
}

OpenClMatcher::OpenClMatcher(const OpenClOptions& options) {
  const std::string inexact = inexact_build_option(options.build_options);
  if (!inexact.empty()) throw std::invalid_argument("OpenCL build options: " + inexact);
  DeviceInfo device;
  try {
    device = select_device(options.platform, options.device);
  } catch (const OpenClError& error) {
    throw OpenClError(std::string("selecting the OpenCL device: ") + error.what(), error.status());
  }
  if (!device.correctly_rounded_divide_sqrt) {
    throw OpenClError("selecting the OpenCL device: " + device.description() +
                          " has no correctly rounded single-precision divide and sqrt, so "
                          "its results could not match the reference",
                      CL_INVALID_DEVICE);
  }
  try {
    state_ = std::make_unique<State>(device, options.profile, options.build_options);
    state_->context.set_memory_budget(options.memory_budget);
  } catch (const OpenClError& error) {
    throw OpenClError("building the kernels on " + device.description() + ": " + error.what(),
                      error.status());
  }
}

OpenClMatcher::~OpenClMatcher() = default;

std::vector<KernelTiming> OpenClMatcher::kernel_timings() const {
  return state_->profiler.summary();
}

size_t OpenClMatcher::peak_buffer_bytes() const { return state_->context.peak_buffer_bytes(); }

std::string OpenClMatcher::device_description() const {
  return state_->context.device().description();
}

StereoResult OpenClMatcher::run(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                                const StereoParams& params, const ProgressCallback& progress) {
  std::string stage = "start";
  state_->context.reset_peak();
  try {
    return run_stages(left_rgb8, right_rgb8, params, progress, stage);
  } catch (const OpenClError& error) {
    throw OpenClError("running on " + device_description() + ", " + stage + ": " + error.what(),
                      error.status());
  }
}

StereoResult OpenClMatcher::run_stages(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                                       const StereoParams& params,
                                       const ProgressCallback& progress, std::string& stage) {
  validate_inputs(left_rgb8, right_rgb8, params);
  auto report = [&](const std::string& what) {
    stage = what;
    if (progress) progress(what);
  };
  stage = "pyramid";
  Context& context = state_->context;
  OpenClStages& stages = state_->stages;
  state_->profiler.clear();
  StereoResult result;
  const int levels = pipeline_level_count(params, left_rgb8.cols, left_rgb8.rows);

  auto start = Clock::now();
  const std::vector<DeviceView> pyramid[2] = {
      build_device_pyramid(stages, left_rgb8, levels, kViewNames[0]),
      build_device_pyramid(stages, right_rgb8, levels, kViewNames[1])};
  const Buffer<float> weights(
      context, make_support_weight_table(params.gamma, params.gamma_distance), "weights");
  context.finish();
  result.timings.push_back({"pyramid", seconds_since(start)});

  DeviceField fields[2];
  Buffer<float> confidence[2];  // of the current level, from the coarser one
  for (int level = levels - 1; level >= 0; --level) {
    start = Clock::now();
    DeviceLevel in;
    in.views[PMS_VIEW_LEFT] = &pyramid[PMS_VIEW_LEFT][level];
    in.views[PMS_VIEW_RIGHT] = &pyramid[PMS_VIEW_RIGHT][level];
    const int width = in.views[0]->width;
    const int height = in.views[0]->height;
    const size_t pixels = static_cast<size_t>(width) * height;
    const LevelPlan plan = plan_level(params, level, levels, width, height);
    stage = plan.name;
    in.weights = &weights;
    in.cost = plan.cost;
    in.ndisp = plan.ndisp;
    in.seed = params.seed;
    // Only this level's records are alive at a time (twice a view's colour and gradient).
    Buffer<float> match[2];
    for (int view = 0; view < 2; ++view) {
      match[view] = Buffer<float>(context, match_record_floats(pixels), "match records");
      stages.pack_match_samples(*in.views[view], match[view]);
      in.match[view] = &match[view];
    }

    for (int view = 0; view < 2; ++view) {
      if (plan.coarsest) {
        fields[view] = make_field(context, width, height, kViewNames[view]);
        stages.init_random_planes(in, view, iteration_key(level, 0), fields[view]);
      } else {
        DeviceField coarse = std::move(fields[view]);
        fields[view] = make_field(context, width, height, kViewNames[view]);
        stages.carry_planes_to_finer(coarse, fields[view]);
        stages.evaluate_costs(in, view, fields[view]);
        Buffer<float> fine_confidence(context, pixels, "confidence");
        stages.upsample_nearest(confidence[view], coarse.width, coarse.height, fine_confidence,
                                width, height);
        confidence[view] = std::move(fine_confidence);
      }
    }

    const Buffer<float>* trusted = plan.use_confidence ? confidence : nullptr;
    for (int iteration = 1; iteration <= plan.iterations; ++iteration) {
      report(plan.iteration_label(iteration));
      run_iteration(stages, in, plan.schedule, iteration_key(level, iteration), trusted,
                    fields);
      // The next iteration trusts what this one made consistent.
      if (plan.refresh_confidence && iteration < plan.iterations) {
        Buffer<float> disparity[2];
        confidence_from_planes(stages, fields, disparity, confidence);
      }
    }

    // The pixels that fail the check start again from the background plane, steered by
    // the check (the confidence); their costs follow their new planes.
    if (plan.refill_iterations > 0) {
      Buffer<float> disparity[2];
      confidence_from_planes(stages, fields, disparity, confidence);
      Buffer<std::uint8_t> consistent[2];
      fill_both_views(stages, disparity, params, fields, consistent);
      // Only the filled pixels' planes changed.
      for (int view = 0; view < 2; ++view) {
        stages.evaluate_costs(in, view, fields[view], &consistent[view]);
      }
      const Buffer<float>* refill_trusted = plan.refill_use_confidence ? confidence : nullptr;
      for (int iteration = 1; iteration <= plan.refill_iterations; ++iteration) {
        report(plan.refill_label(iteration));
        run_iteration(stages, in, plan.refill_schedule,
                      iteration_key(level, plan.iterations + iteration), refill_trusted, fields);
      }
    }

    // The confidence that steers the next level's spatial and random search.
    if (plan.compute_confidence) {
      Buffer<float> disparity[2];
      confidence_from_planes(stages, fields, disparity, confidence);
      if (plan.fill_before_carry) {
        Buffer<std::uint8_t> consistent[2];
        fill_both_views(stages, disparity, params, fields, consistent);
      }
    }
    context.finish();
    result.timings.push_back({plan.name, seconds_since(start)});
  }

  // Post-processing on the finest level.
  start = Clock::now();
  report("post-processing");
  const int width = left_rgb8.cols;
  const int height = left_rgb8.rows;
  const size_t pixels = static_cast<size_t>(width) * height;
  Buffer<float> raw[2] = {Buffer<float>(context, pixels, "raw disparity (left)"),
                          Buffer<float>(context, pixels, "raw disparity (right)")};
  for (int view = 0; view < 2; ++view) stages.plane_disparities(fields[view], raw[view]);
  Buffer<std::uint8_t> consistent(context, pixels, "consistent");
  stages.left_right_check(raw[PMS_VIEW_LEFT], raw[PMS_VIEW_RIGHT], width, height, PMS_VIEW_LEFT,
                          params.lr_tolerance, consistent);
  if (params.raw_speckle_size > 0) {
    Buffer<std::uint8_t> large(context, pixels, "large raw segments");
    stages.large_segment_mask(raw[PMS_VIEW_LEFT], width, height, params.speckle_range,
                              params.raw_speckle_size, large);
    stages.mask_and(large, width, height, consistent);
  }
  DeviceField filled{width, height, Buffer<float>(context, 4 * pixels, "filled planes"),
                     Buffer<float>()};
  stages.fill_inconsistent(fields[PMS_VIEW_LEFT].planes, consistent, width, height,
                           params.fill_max_extrapolation, filled.planes);
  Buffer<float> filled_disparity(context, pixels, "filled disparity");
  stages.plane_disparities(filled, filled_disparity);
  const Buffer<float> median_weights(context, make_support_weight_table(params.median_gamma),
                                     "median weights");
  Buffer<float> filtered(context, pixels, "filtered disparity");
  stages.weighted_median_filled(filled_disparity, consistent, pyramid[PMS_VIEW_LEFT][0],
                                median_weights, params.median_window / 2, params.window_step,
                                params.median_background_margin, filtered);
  const Buffer<float>* final_disparity = &filtered;
  if (params.final_median_window > 1) {
    const Buffer<float> final_weights(
        context, make_support_weight_table(params.final_median_gamma), "final median weights");
    // The filled disparities are no longer needed: the second median writes over them.
    stages.weighted_median_all(filtered, pyramid[PMS_VIEW_LEFT][0], final_weights,
                               params.final_median_window / 2, filled_disparity);
    final_disparity = &filled_disparity;
  }
  Buffer<float> refilled;
  if (params.speckle_size > 0) {
    // Small segments are refilled like inconsistent pixels (see the reference path). The
    // right view's planes are no longer needed: the refill's planes go there.
    Buffer<std::uint8_t> kept(context, pixels, "large segments");
    stages.large_segment_mask(*final_disparity, width, height, params.speckle_range,
                              params.speckle_size, kept);
    DeviceField flat{width, height, Buffer<float>(context, 4 * pixels, "flat planes"),
                     Buffer<float>()};
    stages.flat_planes(*final_disparity, width, height, flat.planes);
    DeviceField& flat_filled = fields[PMS_VIEW_RIGHT];
    stages.fill_inconsistent(flat.planes, kept, width, height, INFINITY, flat_filled.planes);
    flat.planes = Buffer<float>();
    Buffer<float> flat_disparity(context, pixels, "refill's filled disparity");
    stages.plane_disparities(flat_filled, flat_disparity);
    refilled = Buffer<float>(context, pixels, "refilled disparity");
    stages.weighted_median_filled(flat_disparity, kept, pyramid[PMS_VIEW_LEFT][0],
                                  median_weights, params.median_window / 2, params.window_step,
                                  params.median_background_margin, refilled);
    final_disparity = &refilled;
  }
  std::vector<float> disparity = final_disparity->read();
  clamp_to_disparity_range(disparity, params);
  const std::vector<float> raw_left = raw[PMS_VIEW_LEFT].read();
  const std::vector<float> raw_right = raw[PMS_VIEW_RIGHT].read();
  const std::vector<float> planes = filled.planes.read();
  const std::vector<float> cost_left = fields[PMS_VIEW_LEFT].cost.read();
  result.timings.push_back({"post-processing", seconds_since(start)});

  result.disparity = to_mat(disparity, width, height, 1);
  result.raw_left = to_mat(raw_left, width, height, 1);
  result.raw_right = to_mat(raw_right, width, height, 1);
  result.planes_left = planes_to_mat(planes, width, height);
  result.cost_left = to_mat(cost_left, width, height, 1);
  return result;
}

}  // namespace flexsight::opencl

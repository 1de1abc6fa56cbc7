// The OpenCL matcher: a device context with the stereo kernels built, running the
// matcher's one schedule (patchmatch_schedule.h) over the OpenCL stage set.
#include "host/stereo/opencl_matcher.h"

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "host/io/input_error.h"
#include "host/runtime/cl_program.h"
#include "host/stereo/opencl_stage_set.h"
#include "host/stereo/patchmatch_schedule.h"

namespace flexsight::opencl {
namespace {

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
  OpenClStageSet stages;
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
  state_->profiler.clear();
  PatchMatchSchedule<OpenClStageSet> schedule(state_->stages, params, progress, &stage);
  return schedule.run(left_rgb8, right_rgb8);
}

}  // namespace flexsight::opencl

#pragma once
// The OpenCL path of the matcher: the one schedule (patchmatch_schedule.h) over the
// kernels of kernels/stereo/, giving run_stereo's StereoResult byte for byte on a device
// with IEEE single precision and correctly rounded division and square root.
#include <memory>
#include <string>
#include <vector>

#include "host/runtime/cl_context.h"
#include "host/runtime/device_options.h"
#include "host/runtime/kernel_timing.h"
#include "host/stereo/stereo_pipeline.h"

namespace flexsight::opencl {

// Device choice and set-up (host/runtime/device_options.h); the matcher reads every
// field but `kind`.
using OpenClOptions = BackendOptions;

// The stereo kernels built on a device context, kept across runs (building costs
// seconds).
class OpenClMatcher {
 public:
  // Builds the kernels on `context`, which other modules of the process may share
  // (host/runtime/shared_context.h). Throws OpenClError "building the kernels on #0
  // ...: <log>" when they do not build. `profile`: record every kernel launch's time.
  explicit OpenClMatcher(std::shared_ptr<Context> context, bool profile = false);
  // Opens a context of its own first (open_shared_context: "selecting the OpenCL
  // device: ..." when none matches).
  explicit OpenClMatcher(const OpenClOptions& options = {});
  ~OpenClMatcher();
  OpenClMatcher(const OpenClMatcher&) = delete;
  OpenClMatcher& operator=(const OpenClMatcher&) = delete;

  // As run_stereo: same validation (InputError), same result bytes. The timings are
  // wall-clock per stage group, measured after the device finished it. A failing
  // OpenCL call (e.g. out of device memory) throws OpenClError whose message starts
  // with the device and the stage ("running on #0 ..., level 1 (...): ...").
  StereoResult run(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                   const StereoParams& params, const ProgressCallback& progress = {});

  // Per-kernel device times of the last run (empty unless options.profile).
  std::vector<KernelTiming> kernel_timings() const;

  // Device memory the context's buffers held at most during the last run(), in bytes
  // (a shared context counts the other modules' buffers alive meanwhile too).
  size_t peak_buffer_bytes() const;

  // The device, as `flexsight devices` lists it.
  std::string device_description() const;

 private:
  // run() without the error context; `stage` follows the stage that runs.
  StereoResult run_stages(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                          const StereoParams& params, const ProgressCallback& progress,
                          std::string& stage);

  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace flexsight::opencl

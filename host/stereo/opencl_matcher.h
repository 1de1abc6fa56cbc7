#pragma once
// The OpenCL path of the matcher: the reference scheduler's stage list
// (host/stereo/stereo_pipeline.cpp) run with the kernels of kernels/, giving the same
// StereoResult byte for byte on a device with IEEE single precision and correctly
// rounded division and square root.
#include <memory>
#include <string>
#include <vector>

#include "host/runtime/kernel_timing.h"
#include "host/stereo/stereo_pipeline.h"

namespace flexsight::opencl {

struct OpenClOptions {
  // Device selector: empty for the first usable GPU (else the first usable device), a
  // number for an index of enumerate_devices() (host/runtime/cl_device.h; of the
  // platform's devices when `platform` is set), otherwise part of "<platform> <device>"
  // names. `flexsight devices` lists them.
  std::string device;
  // Record every kernel launch's device time (see OpenClMatcher::kernel_timings).
  bool profile = false;
  // Platform selector: empty for every platform, a number for the platform's position,
  // otherwise part of its name.
  std::string platform;
  // Most bytes of device buffers a run may hold at once (0: the device's memory); a run
  // that needs more fails, naming the step and the buffer (see Context::check_allocation).
  size_t memory_budget = 0;
  // Extra OpenCL C build options for every kernel (e.g. -cl-nv-maxrregcount=64 when
  // tuning on a device); the caller refuses inexact ones (inexact_build_option).
  std::string build_options;
};

// True when at least one OpenCL device exists; otherwise false, with the reason in
// *why (when given).
bool opencl_available(std::string* why);

// Holds the device and its built programs across runs (building costs seconds).
class OpenClMatcher {
 public:
  // Throws OpenClError when no device matches or the kernels do not build; the message
  // starts with the step ("selecting the OpenCL device: ...", "building the kernels on
  // #0 ...: ...").
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

  // Device memory the last run() held at most in its buffers, in bytes.
  size_t peak_buffer_bytes() const;

  // The chosen device: DeviceInfo::description(), "#0 pthread-skylake-avx512-AMD EPYC
  // (Portable Computing Language, CPU, OpenCL 3.0 ...)".
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

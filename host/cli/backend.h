#pragma once
// The backend options of the command line (--device, --cl-*), and the stereo module on
// the chosen backend for the stereo and eval commands: the OpenCL matcher
// (host/stereo/opencl_matcher.h, when this build has OpenCL) or run_stereo.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "host/runtime/compute_backend.h"
#include "host/runtime/device_options.h"
#include "host/runtime/kernel_timing.h"
#include "host/stereo/stereo_pipeline.h"

namespace flexsight {

// Removes --device, --cl-platform, --cl-device, --cl-max-memory and --cl-build-options
// with their values from `args`. Throws InputError naming the option for an unknown
// --device value, a --cl-max-memory that is not a positive size, build options that
// would change the results, or a --cl-* option together with --device reference.
BackendOptions take_backend_options(std::vector<std::string>& args);

// "512M" -> 512 MiB: a positive whole number of bytes, or of KiB / MiB / GiB with the
// suffix K, M or G (KiB, MiB, GiB and KB, MB, GB read the same). nullopt otherwise.
std::optional<size_t> parse_byte_size(const std::string& text);

// The --help lines of those options.
std::string backend_options_help();

// The stereo module on the process's backend (host/runtime/compute_backend.h): the
// OpenCL matcher built on the shared context when there is one, the reference path
// otherwise, kept across runs (building the kernels takes seconds).
class StereoBackend {
 public:
  // Builds the matcher on `compute`'s context, which must outlive this. Under opencl a
  // kernel that does not build is an InputError ("--device opencl: building the kernels
  // on ...: <log>"); under auto the reference path runs, with a notice.
  explicit StereoBackend(ComputeBackend& compute);
  // The same with a backend of its own, chosen by `options` (see ComputeBackend).
  explicit StereoBackend(const BackendOptions& options);
  ~StereoBackend();
  StereoBackend(const StereoBackend&) = delete;
  StereoBackend& operator=(const StereoBackend&) = delete;

  // The path the next run() takes: "OpenCL path on #0 <device> (...)" or
  // "reference path".
  std::string planned() const;

  // Matches the pair; `used` (when given) receives the path that produced the result.
  // An OpenCL failure during the run (e.g. out of device memory) throws InputError
  // under opencl and reruns the pair on the reference path, with a notice, under auto.
  // InputError from the inputs themselves passes through.
  StereoResult run(const cv::Mat& left_rgb8, const cv::Mat& right_rgb8,
                   const StereoParams& params, const ProgressCallback& progress = {},
                   std::string* used = nullptr);

  // Per-kernel device times of the last run() when it ran on OpenCL with
  // options.profile; empty otherwise.
  std::vector<opencl::KernelTiming> kernel_timings() const;

  // Device memory the last run() held at most in its buffers (bytes); 0 when the
  // reference path ran.
  size_t peak_device_bytes() const;

 private:
  explicit StereoBackend(std::unique_ptr<ComputeBackend> owned);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One OpenCL device as `flexsight devices` lists it.
struct OpenClDeviceRow {
  int index = 0;              // the number --cl-device takes without --cl-platform
  int platform_index = 0;     // the number --cl-platform takes
  int index_in_platform = 0;  // the number --cl-device takes with --cl-platform
  std::string platform;
  std::string name;
  std::string type;     // "GPU", "CPU", "accelerator", "other"
  std::string version;  // CL_DEVICE_VERSION
  unsigned compute_units = 0;
  unsigned long long global_memory = 0;  // bytes
  unsigned long long max_buffer_bytes = 0;  // the largest single buffer
  bool correctly_rounded_divide_sqrt = false;  // needed by the OpenCL path
  bool is_default = false;  // the device --device auto/opencl picks without --cl-*
};

// Every device OpenCL sees; empty, with the reason in *why, when there is none or this
// build has no OpenCL path.
std::vector<OpenClDeviceRow> list_opencl_device_rows(std::string* why);

}  // namespace flexsight

#pragma once
// The stereo module on the chosen backend (host/runtime/compute_backend.h) for the
// stereo, eval and pick jobs: the OpenCL matcher (host/stereo/opencl_matcher.h, when
// this build has OpenCL) or run_stereo, with the fallback policy between them.
#include <memory>
#include <string>
#include <vector>

#include "host/runtime/compute_backend.h"
#include "host/runtime/kernel_timing.h"
#include "host/stereo/stereo_pipeline.h"

namespace flexsight {

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

}  // namespace flexsight

#pragma once
// The backend choice every module uses: --device auto | opencl | reference, made once
// per process. It opens the shared OpenCL Context (shared_context.h), lets each module
// build its OpenCL part on it, and runs a module's work on the device or on its
// reference path:
//   - opencl: any OpenCL failure (no device, a kernel that does not build, a buffer that
//     does not fit) is an InputError "--device opencl: <step>: <reason>";
//   - auto: the same failure prints one notice line on stderr and the reference path
//     runs, with the same bytes;
//   - reference: no OpenCL at all.
// A --cl-platform or --cl-device that matches nothing is an InputError naming the
// option under auto too, so that a typo never changes the path silently.
#include <exception>
#include <memory>
#include <string>
#include <utility>

#include "host/runtime/device_options.h"

#if defined(FLEXSIGHT_HAVE_OPENCL)
#include "host/runtime/cl_context.h"
#endif

namespace flexsight {

class ComputeBackend {
 public:
  explicit ComputeBackend(const BackendOptions& options);
  ComputeBackend(const ComputeBackend&) = delete;
  ComputeBackend& operator=(const ComputeBackend&) = delete;

  const BackendOptions& options() const { return options_; }
  // "OpenCL path on #0 <device> (...)", or "reference path" when no context is open.
  std::string description() const;

#if defined(FLEXSIGHT_HAVE_OPENCL)
  // The context the modules share; null when the reference path runs.
  const std::shared_ptr<opencl::Context>& context() const { return context_; }

  // A module's OpenCL part, built by `build(context)` on the shared context; null on
  // the reference path, or under auto when it fails (with a notice).
  template <class Part, class Build>
  std::unique_ptr<Part> build_part(Build&& build) {
    if (!context_) return nullptr;
    try {
      return std::forward<Build>(build)(context_);
    } catch (...) {
      device_failed(std::current_exception());
    }
    return nullptr;
  }
#endif

  // on_device() when `device_ready` (the module's OpenCL part exists), else, and after
  // an OpenCL failure under auto, on_reference(). `ran_on_device` (when given) tells
  // which produced the result. Other exceptions (bad input) pass through.
  template <class Device, class Reference>
  auto run(bool device_ready, Device&& on_device, Reference&& on_reference,
           bool* ran_on_device = nullptr) -> decltype(on_reference()) {
    if (device_ready) {
      try {
        auto result = std::forward<Device>(on_device)();
        if (ran_on_device) *ran_on_device = true;
        return result;
      } catch (...) {
        device_failed(std::current_exception());
      }
    }
    if (ran_on_device) *ran_on_device = false;
    return std::forward<Reference>(on_reference)();
  }

 private:
  // Rethrows `error` unless it is an OpenCL failure: as InputError under opencl; under
  // auto it prints the notice and returns, so the caller runs the reference path.
  void device_failed(std::exception_ptr error) const;

  BackendOptions options_;
#if defined(FLEXSIGHT_HAVE_OPENCL)
  std::shared_ptr<opencl::Context> context_;
#endif
};

}  // namespace flexsight

#include "host/runtime/compute_backend.h"

#include <iostream>

#include "host/io/input_error.h"

#if defined(FLEXSIGHT_HAVE_OPENCL)
#include "host/runtime/shared_context.h"
#endif

namespace flexsight {
namespace {

const char* const kReferencePath = "reference path";

// One line: the first of `why` (a build log may follow on further lines, which
// --device opencl shows in full).
void notice_fallback(const std::string& why) {
  std::string line = why.substr(0, why.find('\n'));
  if (line.size() < why.size()) {
    while (!line.empty() && (line.back() == ':' || line.back() == ' ')) line.pop_back();
    line += " (in full with --device opencl)";
  }
  std::cerr << "note: --device auto: " << line << "; running the reference path\n";
}

}  // namespace

#if defined(FLEXSIGHT_HAVE_OPENCL)

ComputeBackend::ComputeBackend(const BackendOptions& options) : options_(options) {
  if (options.kind == BackendKind::Reference) return;
  const bool forced = options.kind == BackendKind::OpenCl;
  std::string why;
  if (!opencl::opencl_available(&why)) {
    if (forced) throw InputError("--device opencl", "selecting the OpenCL device: " + why);
    notice_fallback("no usable OpenCL device (" + why + ")");
    return;
  }
  try {
    context_ = opencl::open_shared_context(options);
  } catch (const opencl::OpenClError& error) {
    // A selector that matches nothing is a typo, not a missing device.
    if (error.status() == CL_INVALID_PLATFORM && !options.cl_platform.empty()) {
      throw InputError("option --cl-platform", error.what());
    }
    if (error.status() == CL_DEVICE_NOT_FOUND && !options.cl_device.empty()) {
      throw InputError("option --cl-device", error.what());
    }
    if (forced) throw InputError("--device opencl", error.what());
    notice_fallback(error.what());
  }
}

std::string ComputeBackend::description() const {
  return context_ ? "OpenCL path on " + context_->device().description() : kReferencePath;
}

void ComputeBackend::device_failed(std::exception_ptr error) const {
  try {
    std::rethrow_exception(error);
  } catch (const opencl::OpenClError& failure) {
    if (options_.kind == BackendKind::OpenCl) throw InputError("--device opencl", failure.what());
    notice_fallback(failure.what());
  }
}

#else  // no OpenCL SDK when this build was configured: the reference path only

namespace {
const char* const kNoOpenCl =
    "this build has no OpenCL path (no OpenCL SDK was found when it was configured)";
}  // namespace

ComputeBackend::ComputeBackend(const BackendOptions& options) : options_(options) {
  if (options.kind == BackendKind::OpenCl) throw InputError("--device opencl", kNoOpenCl);
  if (options.kind == BackendKind::Auto) notice_fallback(kNoOpenCl);
}

std::string ComputeBackend::description() const { return kReferencePath; }

void ComputeBackend::device_failed(std::exception_ptr error) const {
  std::rethrow_exception(error);
}

#endif

}  // namespace flexsight

#pragma once
// The one place that includes the OpenCL C API, pinned to OpenCL 1.2 so that the code
// runs on every driver that matters (NVIDIA still stops at 1.2 for some entry points),
// and the error type every call of this layer throws.
#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>

#include <stdexcept>
#include <string>

namespace flexsight::opencl {

// A failed OpenCL call, described as a sentence: "<call> on '<subject>': <CODE>: <meaning>".
class OpenClError : public std::runtime_error {
 public:
  OpenClError(const std::string& message, cl_int status)
      : std::runtime_error(message), status_(status) {}
  cl_int status() const { return status_; }

 private:
  cl_int status_;
};

// "CL_OUT_OF_RESOURCES" for -5, "CL_ERROR_<n>" for codes this layer does not know.
std::string status_name(cl_int status);

// What the status means for the caller, in a few words.
std::string status_meaning(cl_int status);

// The sentence of OpenClError for a failed `call` on `subject` (a device, kernel, ...).
std::string describe_failure(const char* call, const std::string& subject, cl_int status);

// Throws OpenClError unless status is CL_SUCCESS.
inline void check(cl_int status, const char* call, const std::string& subject) {
  if (status != CL_SUCCESS) throw OpenClError(describe_failure(call, subject, status), status);
}

}  // namespace flexsight::opencl

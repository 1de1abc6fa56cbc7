#pragma once
// Opening the one OpenCL Context every module of a process shares (the stereo matcher
// and, on the camera, the detector's post-processing): a device whose arithmetic can
// match the reference paths, the user's build options and the memory budget. Each
// module builds its programs into it (the program cache is per context).
#include <memory>
#include <string>

#include "host/runtime/cl_context.h"
#include "host/runtime/device_options.h"

namespace flexsight::opencl {

// True when at least one OpenCL device exists; otherwise false, with the reason in
// *why (when given).
bool opencl_available(std::string* why);

// Selects the device of options.cl_platform / cl_device (select_device) and opens a
// context on it. Throws std::invalid_argument for build options that would change the
// results (inexact_build_option), OpenClError whose message starts with "selecting the
// OpenCL device: " when none matches or its divide and sqrt are not correctly rounded.
std::shared_ptr<Context> open_shared_context(const BackendOptions& options);

}  // namespace flexsight::opencl

#pragma once
// What a user chooses about the compute device, for every module of a process alike:
// the path (--device auto|opencl|reference) and, for OpenCL, which device and how it
// is set up (--cl-platform, --cl-device, --cl-max-memory, --cl-build-options). No
// OpenCL types here, so that a build without OpenCL compiles it too.
#include <cstddef>
#include <string>

namespace flexsight {

enum class BackendKind {
  Auto,       // OpenCL when a usable device exists, else the reference path (with a notice)
  OpenCl,     // OpenCL or an error
  Reference,  // the scalar reference path
};

struct BackendOptions {
  BackendKind kind = BackendKind::Auto;
  // A platform's number or part of its name; "" for every platform.
  std::string cl_platform;
  // A device's number (within cl_platform when given) or part of its name; "" for the
  // first GPU that rounds divide and sqrt correctly, else the first such device.
  std::string cl_device;
  // Most bytes of device buffers the process may hold at once; 0 for the device's
  // memory. A run that needs more fails (opencl) or falls back (auto).
  size_t cl_max_memory = 0;
  // Extra OpenCL C build options for every kernel, for tuning on a device (e.g.
  // "-cl-nv-maxrregcount=64"); options that would change the results are refused.
  std::string cl_build_options;
  // Record the device time of every kernel launch.
  bool profile = false;
};

}  // namespace flexsight

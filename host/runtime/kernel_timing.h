#pragma once
// Device time of one kernel over a run, for --profile (no OpenCL types, so the CLI can
// print it without the OpenCL headers).
#include <string>

namespace flexsight::opencl {

struct KernelTiming {
  std::string kernel;
  int launches = 0;
  double seconds = 0;  // device time, summed over the launches
};

}  // namespace flexsight::opencl

#pragma once
// Device times of kernel launches, summed per kernel, for --profile. Events are kept
// and only queried at the end, so profiling adds no synchronisation to the pipeline.
#include <string>
#include <utility>
#include <vector>

#include "host/runtime/cl_kernel.h"
#include "host/runtime/kernel_timing.h"

namespace flexsight::opencl {

class KernelProfiler {
 public:
  void record(const std::string& kernel, Event event);
  // One entry per kernel in the order of first launch (waits for pending launches).
  std::vector<KernelTiming> summary() const;
  void clear() { events_.clear(); }

 private:
  std::vector<std::pair<std::string, Event>> events_;
};

}  // namespace flexsight::opencl

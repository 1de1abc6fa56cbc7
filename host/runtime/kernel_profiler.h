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

// Launches `kernel` over width x height items and, when there is a profiler, hands it
// the launch's event: what every stage set does for each kernel it runs.
inline void launch_profiled(Kernel& kernel, size_t width, size_t height,
                            KernelProfiler* profiler) {
  Event event = kernel.launch(width, height);
  if (profiler) profiler->record(kernel.name(), std::move(event));
}

}  // namespace flexsight::opencl

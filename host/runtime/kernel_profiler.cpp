#include "host/runtime/kernel_profiler.h"

#include <algorithm>

namespace flexsight::opencl {

void KernelProfiler::record(const std::string& kernel, Event event) {
  events_.emplace_back(kernel, std::move(event));
}

std::vector<KernelTiming> KernelProfiler::summary() const {
  std::vector<KernelTiming> timings;
  for (const auto& [kernel, event] : events_) {
    auto it = std::find_if(timings.begin(), timings.end(),
                           [&](const KernelTiming& t) { return t.kernel == kernel; });
    if (it == timings.end()) it = timings.insert(timings.end(), KernelTiming{kernel, 0, 0.0});
    it->launches += 1;
    it->seconds += event.device_seconds(kernel);
  }
  return timings;
}

}  // namespace flexsight::opencl

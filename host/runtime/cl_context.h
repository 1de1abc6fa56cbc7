#pragma once
// One device with its context, an in-order queue with profiling (event timings cost
// next to nothing and make --profile possible without a second code path), and the
// programs built for it.
#include <string>

#include "host/runtime/cl_device.h"
#include "host/runtime/cl_handle.h"
#include "host/runtime/cl_program.h"

namespace flexsight::opencl {

class Context {
 public:
  // Throws OpenClError when the context or queue cannot be created. `user_build_options`
  // go after every program's own options (see inexact_build_option for what the callers
  // refuse); a program that fails to build with them throws with its build log.
  explicit Context(const DeviceInfo& device, std::string user_build_options = {});
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  // Waits for the queue (errors ignored: destructors never throw).
  ~Context();

  const DeviceInfo& device() const { return device_; }
  cl_context context() const { return context_.get(); }
  cl_command_queue queue() const { return queue_.get(); }
  // Largest work-group size and per-dimension work-item counts of the device.
  size_t max_work_group_size() const { return max_work_group_size_; }
  size_t max_work_item_size(int dimension) const { return max_work_item_sizes_[dimension]; }

  cl_program program(const KernelSource& source, const std::string& extra_options = {}) {
    std::string options = extra_options;
    if (!user_build_options_.empty()) {
      options += (options.empty() ? "" : " ") + user_build_options_;
    }
    return programs_.get(context_.get(), device_, source, options);
  }
  const ProgramCache& programs() const { return programs_; }

  // Blocks until every enqueued command has finished; throws on a failed command.
  void finish();

  // Bytes of the Buffers alive on this context now, and the most alive at once since
  // the last reset_peak(): the device memory a run needs (programs and the runtime's
  // own allocations are not counted).
  size_t buffer_bytes() const { return buffer_bytes_; }
  size_t peak_buffer_bytes() const { return peak_buffer_bytes_; }
  void reset_peak() { peak_buffer_bytes_ = buffer_bytes_; }
  // Device memory this context's buffers may hold at once: `bytes`, or 0 for the
  // device's global memory. A camera shares its GPU with the detector, so a run can be
  // held to a share of it; and a run that does not fit fails at the first buffer that
  // does not, naming it, instead of wherever the driver notices (drivers allocate lazily).
  void set_memory_budget(size_t bytes) { memory_budget_ = bytes; }
  size_t memory_budget() const { return memory_budget_; }
  // Throws OpenClError (CL_INVALID_BUFFER_SIZE: larger than the device's largest
  // buffer; CL_MEM_OBJECT_ALLOCATION_FAILURE: the live buffers would exceed the budget
  // or the device's memory) unless a buffer of `bytes` called `what` may be created.
  void check_allocation(size_t bytes, const std::string& what) const;
  void note_allocated(size_t bytes) {
    buffer_bytes_ += bytes;
    if (buffer_bytes_ > peak_buffer_bytes_) peak_buffer_bytes_ = buffer_bytes_;
  }
  void note_released(size_t bytes) { buffer_bytes_ -= bytes; }

 private:
  DeviceInfo device_;
  std::string user_build_options_;
  ContextHandle context_;
  QueueHandle queue_;
  ProgramCache programs_;
  size_t max_work_group_size_ = 1;
  size_t max_work_item_sizes_[3] = {1, 1, 1};
  size_t buffer_bytes_ = 0;
  size_t peak_buffer_bytes_ = 0;
  size_t memory_budget_ = 0;
};

}  // namespace flexsight::opencl

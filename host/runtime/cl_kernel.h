#pragma once
// One kernel of a built program: arguments set from a parameter pack (buffers, optional
// buffers and plain values, checked against the kernel's argument count) and 2-D
// launches over a pixel range, with the work sizes checked before the enqueue.
#include <string>
#include <type_traits>

#include "host/runtime/cl_buffer.h"

namespace flexsight::opencl {

// A finished-or-pending command; its profiling times once it has completed.
class Event {
 public:
  Event() = default;
  explicit Event(cl_event event) : event_(event) {}
  cl_event get() const { return event_.get(); }
  // Seconds between the command's start and end on the device (waits for it).
  double device_seconds(const std::string& what) const;

 private:
  EventHandle event_;
};

class Kernel {
 public:
  Kernel() = default;
  Kernel(Context& context, cl_program program, const char* name);
  // The kernel `name` of `source` built on `context` with `options` (the context caches
  // the program per source and options, so many kernels of one file build it once).
  Kernel(Context& context, const KernelSource& source, const char* name,
         const std::string& options = {})
      : Kernel(context, context.program(source, options), name) {}

  const std::string& name() const { return name_; }

  // Sets every argument, in order; throws when their number differs from the kernel's.
  template <typename... Args>
  void set_args(const Args&... args) {
    require_argument_count(sizeof...(Args));
    cl_uint index = 0;
    (set_one(index++, args), ...);
  }

  // Launches over `items` (width x height work items), each dimension rounded up to
  // the work-group size; the kernel skips the items past its range. Throws for an
  // empty range or a work group the kernel or device cannot run.
  Event launch(size_t width, size_t height);

 private:
  template <typename T>
  void set_one(cl_uint index, const Buffer<T>& buffer) {
    cl_mem mem = buffer.get();
    set_raw(index, sizeof mem, &mem);
  }
  // A null pointer passes a NULL __global pointer (an optional input).
  template <typename T>
  void set_one(cl_uint index, const Buffer<T>* buffer) {
    cl_mem mem = buffer ? buffer->get() : nullptr;
    set_raw(index, sizeof mem, buffer ? &mem : nullptr);
  }
  template <typename T>
  void set_one(cl_uint index, const T& value) {
    static_assert(std::is_trivially_copyable_v<T> && !std::is_pointer_v<T>,
                  "kernel arguments are buffers or plain values");
    set_raw(index, sizeof value, &value);
  }
  void set_raw(cl_uint index, size_t size, const void* value);
  void require_argument_count(size_t count) const;

  Context* context_ = nullptr;
  std::string name_;
  KernelHandle kernel_;
  size_t local_[2] = {1, 1};
};

}  // namespace flexsight::opencl

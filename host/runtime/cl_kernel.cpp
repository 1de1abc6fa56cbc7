#include "host/runtime/cl_kernel.h"

#include <climits>

namespace flexsight::opencl {
namespace {

// 16 x 4: 64 work items, a multiple of every GPU's SIMD width and what PoCL
// vectorises well; rows of 16 keep the window reads of neighbours close together.
constexpr size_t kPreferredLocal[2] = {16, 4};

size_t round_up(size_t value, size_t multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

}  // namespace

double Event::device_seconds(const std::string& what) const {
  cl_event event = event_.get();
  check(clWaitForEvents(1, &event), "clWaitForEvents", what);
  cl_ulong start = 0;
  cl_ulong end = 0;
  check(clGetEventProfilingInfo(event, CL_PROFILING_COMMAND_START, sizeof start, &start, nullptr),
        "clGetEventProfilingInfo", what);
  check(clGetEventProfilingInfo(event, CL_PROFILING_COMMAND_END, sizeof end, &end, nullptr),
        "clGetEventProfilingInfo", what);
  return end > start ? static_cast<double>(end - start) * 1e-9 : 0.0;
}

Kernel::Kernel(Context& context, cl_program program, const char* name)
    : context_(&context), name_(name) {
  cl_int status = CL_SUCCESS;
  kernel_ = KernelHandle(clCreateKernel(program, name, &status));
  check(status, "clCreateKernel", name_);

  // The work group: the preferred one, halved until the kernel (its private memory
  // can limit it) and the device accept it.
  size_t kernel_limit = 0;
  check(clGetKernelWorkGroupInfo(kernel_.get(), context.device().device, CL_KERNEL_WORK_GROUP_SIZE,
                                 sizeof kernel_limit, &kernel_limit, nullptr),
        "clGetKernelWorkGroupInfo", name_);
  for (int d = 0; d < 2; ++d) local_[d] = kPreferredLocal[d];
  while (local_[0] * local_[1] > kernel_limit || local_[0] > context.max_work_item_size(0) ||
         local_[1] > context.max_work_item_size(1)) {
    if (local_[0] == 1 && local_[1] == 1) break;
    int d = (local_[0] >= local_[1] && local_[0] > 1) ? 0 : 1;
    local_[d] /= 2;
  }
}

void Kernel::set_raw(cl_uint index, size_t size, const void* value) {
  check(clSetKernelArg(kernel_.get(), index, size, value), "clSetKernelArg",
        name_ + " argument " + std::to_string(index));
}

void Kernel::require_argument_count(size_t count) const {
  cl_uint expected = 0;
  check(clGetKernelInfo(kernel_.get(), CL_KERNEL_NUM_ARGS, sizeof expected, &expected, nullptr),
        "clGetKernelInfo", name_);
  if (count != expected) {
    throw std::logic_error("kernel '" + name_ + "' takes " + std::to_string(expected) +
                           " arguments, the host passes " + std::to_string(count));
  }
}

Event Kernel::launch(size_t width, size_t height) {
  if (width == 0 || height == 0) {
    throw std::invalid_argument("kernel '" + name_ + "': empty launch range " +
                                std::to_string(width) + "x" + std::to_string(height));
  }
  // Checked here rather than left to the driver, whose error codes do not say which
  // limit was hit.
  if (local_[0] * local_[1] > context_->max_work_group_size()) {
    throw std::logic_error("kernel '" + name_ + "': work group " + std::to_string(local_[0]) + "x" +
                           std::to_string(local_[1]) + " exceeds the device's limit");
  }
  const size_t global[2] = {round_up(width, local_[0]), round_up(height, local_[1])};
  // The kernels index pixels with int, as the reference does.
  if (global[0] > static_cast<size_t>(INT_MAX) || global[1] > static_cast<size_t>(INT_MAX) ||
      width * height > static_cast<size_t>(INT_MAX) / 4) {
    throw std::invalid_argument("kernel '" + name_ + "': launch range " + std::to_string(width) +
                                "x" + std::to_string(height) + " is too large for int indices");
  }
  cl_event event = nullptr;
  check(clEnqueueNDRangeKernel(context_->queue(), kernel_.get(), 2, nullptr, global, local_, 0,
                               nullptr, &event),
        "clEnqueueNDRangeKernel", name_);
  return Event(event);
}

}  // namespace flexsight::opencl

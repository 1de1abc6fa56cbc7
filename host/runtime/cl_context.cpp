#include "host/runtime/cl_context.h"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace flexsight::opencl {

Context::Context(const DeviceInfo& device, std::string user_build_options)
    : device_(device), user_build_options_(std::move(user_build_options)) {
  cl_int status = CL_SUCCESS;
  const cl_context_properties properties[] = {
      CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(device.platform), 0};
  context_ = ContextHandle(
      clCreateContext(properties, 1, &device.device, nullptr, nullptr, &status));
  check(status, "clCreateContext", device.name);
  // clCreateCommandQueue is the 1.2 entry point (deprecated, still present, in 2.0+).
  queue_ = QueueHandle(clCreateCommandQueue(context_.get(), device.device,
                                            CL_QUEUE_PROFILING_ENABLE, &status));
  check(status, "clCreateCommandQueue", device.name);
  check(clGetDeviceInfo(device.device, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof max_work_group_size_,
                        &max_work_group_size_, nullptr),
        "clGetDeviceInfo", device.name);
  check(clGetDeviceInfo(device.device, CL_DEVICE_MAX_WORK_ITEM_SIZES,
                        sizeof max_work_item_sizes_, max_work_item_sizes_, nullptr),
        "clGetDeviceInfo", device.name);
}

Context::~Context() {
  if (queue_) clFinish(queue_.get());
}

namespace {

std::string mebibytes(size_t bytes) {
  const double mib = static_cast<double>(bytes) / (1024.0 * 1024.0);
  char text[32];
  std::snprintf(text, sizeof text, mib < 10.0 ? "%.2f MiB" : "%.0f MiB", mib);
  return text;
}

}  // namespace

void Context::check_allocation(size_t bytes, const std::string& what) const {
  if (device_.max_buffer_bytes > 0 && bytes > device_.max_buffer_bytes) {
    throw OpenClError("creating buffer '" + what + "': it needs " +
                          mebibytes(bytes) + ", more than the largest buffer the device allows (" +
                          mebibytes(device_.max_buffer_bytes) + ")",
                      CL_INVALID_BUFFER_SIZE);
  }
  const bool budgeted = memory_budget_ > 0 &&
                        (device_.global_memory == 0 || memory_budget_ < device_.global_memory);
  const size_t limit = budgeted ? memory_budget_ : device_.global_memory;
  if (limit > 0 && bytes > limit - std::min(limit, buffer_bytes_)) {
    throw OpenClError("creating buffer '" + what + "': its " +
                          mebibytes(bytes) + " would bring the live buffers to " +
                          mebibytes(buffer_bytes_ + bytes) + ", over " +
                          (budgeted ? "this run's device memory budget of " + mebibytes(limit)
                                    : "the device's " + mebibytes(limit) + " of global memory"),
                      CL_MEM_OBJECT_ALLOCATION_FAILURE);
  }
}

void Context::finish() { check(clFinish(queue_.get()), "clFinish", device_.name); }

}  // namespace flexsight::opencl

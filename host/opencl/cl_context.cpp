#include "host/opencl/cl_context.h"

namespace flexsight::opencl {

Context::Context(const DeviceInfo& device) : device_(device) {
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

void Context::finish() { check(clFinish(queue_.get()), "clFinish", device_.name); }

}  // namespace flexsight::opencl

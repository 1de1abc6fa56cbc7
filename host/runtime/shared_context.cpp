#include "host/runtime/shared_context.h"

#include <stdexcept>

namespace flexsight::opencl {

bool opencl_available(std::string* why) {
  try {
    if (!enumerate_devices().empty()) return true;
    if (why) *why = "no OpenCL platform or device is installed";
  } catch (const OpenClError& error) {
    if (why) *why = error.what();
  }
  return false;
}

std::shared_ptr<Context> open_shared_context(const BackendOptions& options) {
  const std::string inexact = inexact_build_option(options.cl_build_options);
  if (!inexact.empty()) throw std::invalid_argument("OpenCL build options: " + inexact);
  DeviceInfo device;
  try {
    device = select_device(options.cl_platform, options.cl_device);
  } catch (const OpenClError& error) {
    throw OpenClError(std::string("selecting the OpenCL device: ") + error.what(), error.status());
  }
  if (!device.correctly_rounded_divide_sqrt) {
    throw OpenClError("selecting the OpenCL device: " + device.description() +
                          " has no correctly rounded single-precision divide and sqrt, so "
                          "its results could not match the reference",
                      CL_INVALID_DEVICE);
  }
  try {
    auto context = std::make_shared<Context>(device, options.cl_build_options);
    context->set_memory_budget(options.cl_max_memory);
    return context;
  } catch (const OpenClError& error) {
    throw OpenClError("opening a context on " + device.description() + ": " + error.what(),
                      error.status());
  }
}

}  // namespace flexsight::opencl

#pragma once
// OpenCL platforms and devices: listing them and choosing one by index or by name.
#include <string>
#include <vector>

#include "host/opencl/cl_api.h"

namespace flexsight::opencl {

struct DeviceInfo {
  cl_platform_id platform = nullptr;
  cl_device_id device = nullptr;
  int index = 0;  // position in enumerate_devices()
  std::string platform_name;
  std::string name;
  std::string version;  // CL_DEVICE_VERSION
  cl_device_type type = 0;
  // -cl-fp32-correctly-rounded-divide-sqrt is accepted: without it the kernels'
  // divisions and square roots may differ from the reference in the last bit.
  bool correctly_rounded_divide_sqrt = false;
  // "#0 pthread-skylake (Portable Computing Language, CPU, OpenCL 3.0 PoCL ...)"
  std::string description() const;
};

// Every device of every platform, platforms in the ICD loader's order. Empty when no
// platform is installed; throws OpenClError for other failures.
std::vector<DeviceInfo> enumerate_devices();

// `selector`: empty for the first GPU (the first device when there is none), a
// number for that index of enumerate_devices(), otherwise a case-insensitive part of
// "<platform name> <device name>" (the first match). Throws OpenClError (no platform,
// no match) with the list of devices in the message.
DeviceInfo select_device(const std::string& selector);

}  // namespace flexsight::opencl

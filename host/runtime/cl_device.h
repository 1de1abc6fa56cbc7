#pragma once
// OpenCL platforms and devices: listing them and choosing one by index or by name.
#include <string>
#include <vector>

#include "host/runtime/cl_api.h"

namespace flexsight::opencl {

struct DeviceInfo {
  cl_platform_id platform = nullptr;
  cl_device_id device = nullptr;
  int index = 0;              // position in enumerate_devices()
  int platform_index = 0;     // position of the platform in the ICD loader's list
  int index_in_platform = 0;  // position among the devices of its platform
  std::string platform_name;
  std::string name;
  std::string version;         // CL_DEVICE_VERSION
  std::string driver_version;  // CL_DRIVER_VERSION (benchmark reports name the driver)
  cl_device_type type = 0;
  cl_uint compute_units = 0;      // CL_DEVICE_MAX_COMPUTE_UNITS
  cl_ulong global_memory = 0;     // CL_DEVICE_GLOBAL_MEM_SIZE, bytes
  cl_ulong max_buffer_bytes = 0;  // CL_DEVICE_MAX_MEM_ALLOC_SIZE: the largest one buffer
  // -cl-fp32-correctly-rounded-divide-sqrt is accepted: without it the kernels'
  // divisions and square roots may differ from the reference in the last bit.
  bool correctly_rounded_divide_sqrt = false;
  // "#0 pthread-skylake (Portable Computing Language, CPU, OpenCL 3.0 PoCL ...)"
  std::string description() const;
  // "GPU", "CPU", "accelerator" or "other".
  const char* type_name() const;
};

// Every device of every platform, platforms in the ICD loader's order. Empty when no
// platform is installed; throws OpenClError for other failures.
std::vector<DeviceInfo> enumerate_devices();

// `selector`: empty for the first GPU (the first device when there is none), a
// number for that index of enumerate_devices(), otherwise a case-insensitive part of
// "<platform name> <device name>" (the first match). Throws OpenClError (no platform,
// no match) with the list of devices in the message. Devices without correctly rounded
// divide and sqrt (which the matcher cannot use) are chosen by default only when no
// other device exists.
DeviceInfo select_device(const std::string& selector);

// As select_device(device_selector), among the devices of one platform:
// `platform_selector` is empty for every platform, a number for that platform's
// position, otherwise a case-insensitive part of its name (the first match); a number
// in `device_selector` then counts the devices of that platform only.
DeviceInfo select_device(const std::string& platform_selector,
                         const std::string& device_selector);

}  // namespace flexsight::opencl

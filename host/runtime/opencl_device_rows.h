#pragma once
// The OpenCL devices this process sees, as `flexsight devices` lists them.
#include <string>
#include <vector>

namespace flexsight {

// One OpenCL device as `flexsight devices` lists it.
struct OpenClDeviceRow {
  int index = 0;              // the number --cl-device takes without --cl-platform
  int platform_index = 0;     // the number --cl-platform takes
  int index_in_platform = 0;  // the number --cl-device takes with --cl-platform
  std::string platform;
  std::string name;
  std::string type;     // "GPU", "CPU", "accelerator", "other"
  std::string version;  // CL_DEVICE_VERSION
  unsigned compute_units = 0;
  unsigned long long global_memory = 0;  // bytes
  unsigned long long max_buffer_bytes = 0;  // the largest single buffer
  bool correctly_rounded_divide_sqrt = false;  // needed by the OpenCL path
  bool is_default = false;  // the device --device auto/opencl picks without --cl-*
};

// Every device OpenCL sees; empty, with the reason in *why, when there is none or this
// build has no OpenCL path.
std::vector<OpenClDeviceRow> list_opencl_device_rows(std::string* why);

}  // namespace flexsight

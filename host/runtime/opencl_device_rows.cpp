#include "host/runtime/opencl_device_rows.h"

#if defined(FLEXSIGHT_HAVE_OPENCL)
#include "host/runtime/cl_device.h"
#endif

namespace flexsight {

#if defined(FLEXSIGHT_HAVE_OPENCL)

std::vector<OpenClDeviceRow> list_opencl_device_rows(std::string* why) {
  std::vector<OpenClDeviceRow> rows;
  try {
    const std::vector<opencl::DeviceInfo> devices = opencl::enumerate_devices();
    if (devices.empty()) {
      if (why) *why = "no OpenCL platform with a device is installed";
      return rows;
    }
    const int default_index = opencl::select_device("", "").index;
    for (const opencl::DeviceInfo& d : devices) {
      OpenClDeviceRow row;
      row.index = d.index;
      row.platform_index = d.platform_index;
      row.index_in_platform = d.index_in_platform;
      row.platform = d.platform_name;
      row.name = d.name;
      row.type = d.type_name();
      row.version = d.version;
      row.compute_units = d.compute_units;
      row.global_memory = d.global_memory;
      row.max_buffer_bytes = d.max_buffer_bytes;
      row.correctly_rounded_divide_sqrt = d.correctly_rounded_divide_sqrt;
      row.is_default = d.index == default_index;
      rows.push_back(row);
    }
  } catch (const opencl::OpenClError& error) {
    rows.clear();
    if (why) *why = error.what();
  }
  return rows;
}

#else  // no OpenCL SDK when this build was configured

namespace {
const char* const kNoOpenCl =
    "this build has no OpenCL path (no OpenCL SDK was found when it was configured)";
}  // namespace

std::vector<OpenClDeviceRow> list_opencl_device_rows(std::string* why) {
  if (why) *why = kNoOpenCl;
  return {};
}

#endif

}  // namespace flexsight

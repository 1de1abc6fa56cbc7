#include "host/opencl/cl_device.h"

#include <algorithm>
#include <cctype>

namespace flexsight::opencl {
namespace {

// CL_PLATFORM_NOT_FOUND_KHR: the ICD loader's answer when no platform is installed.
constexpr cl_int kPlatformNotFoundKhr = -1001;

std::string platform_string(cl_platform_id platform, cl_platform_info what) {
  size_t size = 0;
  check(clGetPlatformInfo(platform, what, 0, nullptr, &size), "clGetPlatformInfo", "platform");
  std::string text(size, '\0');
  check(clGetPlatformInfo(platform, what, size, text.data(), nullptr), "clGetPlatformInfo",
        "platform");
  return text.c_str();  // drops the terminating zero
}

std::string device_string(cl_device_id device, cl_device_info what) {
  size_t size = 0;
  check(clGetDeviceInfo(device, what, 0, nullptr, &size), "clGetDeviceInfo", "device");
  std::string text(size, '\0');
  check(clGetDeviceInfo(device, what, size, text.data(), nullptr), "clGetDeviceInfo", "device");
  return text.c_str();
}

template <typename T>
T device_value(cl_device_id device, cl_device_info what) {
  T value{};
  check(clGetDeviceInfo(device, what, sizeof value, &value, nullptr), "clGetDeviceInfo",
        "device");
  return value;
}

const char* type_name(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "GPU";
  if (type & CL_DEVICE_TYPE_CPU) return "CPU";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool all_digits(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(),
                                      [](unsigned char c) { return std::isdigit(c) != 0; });
}

std::string device_list(const std::vector<DeviceInfo>& devices) {
  std::string list;
  for (const DeviceInfo& d : devices) list += "\n  " + d.description();
  return list.empty() ? " (none)" : list;
}

}  // namespace

std::string DeviceInfo::description() const {
  return "#" + std::to_string(index) + " " + name + " (" + platform_name + ", " +
         type_name(type) + ", " + version + ")";
}

std::vector<DeviceInfo> enumerate_devices() {
  cl_uint platform_count = 0;
  cl_int status = clGetPlatformIDs(0, nullptr, &platform_count);
  if (status == kPlatformNotFoundKhr || platform_count == 0) return {};
  check(status, "clGetPlatformIDs", "OpenCL ICD loader");
  std::vector<cl_platform_id> platforms(platform_count);
  check(clGetPlatformIDs(platform_count, platforms.data(), nullptr), "clGetPlatformIDs",
        "OpenCL ICD loader");

  std::vector<DeviceInfo> devices;
  for (cl_platform_id platform : platforms) {
    const std::string platform_name = platform_string(platform, CL_PLATFORM_NAME);
    cl_uint count = 0;
    status = clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 0, nullptr, &count);
    if (status == CL_DEVICE_NOT_FOUND || count == 0) continue;
    check(status, "clGetDeviceIDs", platform_name);
    std::vector<cl_device_id> ids(count);
    check(clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, count, ids.data(), nullptr),
          "clGetDeviceIDs", platform_name);
    for (cl_device_id id : ids) {
      DeviceInfo info;
      info.platform = platform;
      info.device = id;
      info.index = static_cast<int>(devices.size());
      info.platform_name = platform_name;
      info.name = device_string(id, CL_DEVICE_NAME);
      info.version = device_string(id, CL_DEVICE_VERSION);
      info.type = device_value<cl_device_type>(id, CL_DEVICE_TYPE);
      info.correctly_rounded_divide_sqrt =
          (device_value<cl_device_fp_config>(id, CL_DEVICE_SINGLE_FP_CONFIG) &
           CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
      devices.push_back(info);
    }
  }
  return devices;
}

DeviceInfo select_device(const std::string& selector) {
  const std::vector<DeviceInfo> devices = enumerate_devices();
  if (devices.empty()) {
    throw OpenClError(describe_failure("clGetPlatformIDs", "OpenCL ICD loader",
                                       kPlatformNotFoundKhr) +
                          " (install a driver, e.g. pocl-opencl-icd for the CPU)",
                      kPlatformNotFoundKhr);
  }
  if (selector.empty()) {
    for (const DeviceInfo& d : devices) {
      if (d.type & CL_DEVICE_TYPE_GPU) return d;
    }
    return devices.front();
  }
  if (all_digits(selector)) {
    // At most 9 digits, so that stoul cannot overflow; no machine has more devices.
    size_t index = selector.size() <= 9 ? std::stoul(selector) : devices.size();
    if (index < devices.size()) return devices[index];
  } else {
    for (const DeviceInfo& d : devices) {
      if (lower(d.platform_name + " " + d.name).find(lower(selector)) != std::string::npos) {
        return d;
      }
    }
  }
  throw OpenClError("no OpenCL device matches '" + selector + "'; the devices are:" +
                        device_list(devices),
                    CL_DEVICE_NOT_FOUND);
}

}  // namespace flexsight::opencl

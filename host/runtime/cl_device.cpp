#include "host/runtime/cl_device.h"

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

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool all_digits(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(),
                                      [](unsigned char c) { return std::isdigit(c) != 0; });
}

// One line per device; `within_platform` puts the number a selector counts in that
// platform first.
std::string device_list(const std::vector<DeviceInfo>& devices, bool within_platform = false) {
  std::string list;
  for (const DeviceInfo& d : devices) {
    list += "\n  ";
    if (within_platform) list += std::to_string(d.index_in_platform) + ": ";
    list += d.description();
  }
  return list.empty() ? " (none)" : list;
}

// "\n  #0 Portable Computing Language" for every platform with a device.
std::string platform_list(const std::vector<DeviceInfo>& devices) {
  std::string list;
  int last = -1;
  for (const DeviceInfo& d : devices) {
    if (d.platform_index == last) continue;
    last = d.platform_index;
    list += "\n  #" + std::to_string(d.platform_index) + " " + d.platform_name;
  }
  return list.empty() ? " (none)" : list;
}

// The devices of the platform `selector` names (every device when it is empty).
std::vector<DeviceInfo> platform_devices(const std::vector<DeviceInfo>& devices,
                                         const std::string& selector) {
  if (selector.empty()) return devices;
  std::vector<DeviceInfo> chosen;
  if (all_digits(selector)) {
    // At most 9 digits, so that stoi cannot overflow; no machine has more platforms.
    const int index = selector.size() <= 9 ? std::stoi(selector) : -1;
    for (const DeviceInfo& d : devices) {
      if (d.platform_index == index) chosen.push_back(d);
    }
  } else {
    for (const DeviceInfo& d : devices) {
      if (!chosen.empty() && d.platform_index != chosen.front().platform_index) continue;
      if (lower(d.platform_name).find(lower(selector)) != std::string::npos) chosen.push_back(d);
    }
  }
  if (chosen.empty()) {
    throw OpenClError("no OpenCL platform with a device matches '" + selector +
                          "'; the platforms are:" + platform_list(devices),
                      CL_INVALID_PLATFORM);
  }
  return chosen;
}

}  // namespace

const char* DeviceInfo::type_name() const {
  if (type & CL_DEVICE_TYPE_GPU) return "GPU";
  if (type & CL_DEVICE_TYPE_CPU) return "CPU";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

std::string DeviceInfo::description() const {
  return "#" + std::to_string(index) + " " + name + " (" + platform_name + ", " + type_name() +
         ", " + version + ")";
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
  for (cl_uint platform_index = 0; platform_index < platform_count; ++platform_index) {
    const cl_platform_id platform = platforms[platform_index];
    const std::string platform_name = platform_string(platform, CL_PLATFORM_NAME);
    cl_uint count = 0;
    status = clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 0, nullptr, &count);
    if (status == CL_DEVICE_NOT_FOUND || count == 0) continue;
    check(status, "clGetDeviceIDs", platform_name);
    std::vector<cl_device_id> ids(count);
    check(clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, count, ids.data(), nullptr),
          "clGetDeviceIDs", platform_name);
    for (cl_uint i = 0; i < count; ++i) {
      const cl_device_id id = ids[i];
      DeviceInfo info;
      info.platform = platform;
      info.device = id;
      info.index = static_cast<int>(devices.size());
      info.platform_index = static_cast<int>(platform_index);
      info.index_in_platform = static_cast<int>(i);
      info.platform_name = platform_name;
      info.name = device_string(id, CL_DEVICE_NAME);
      info.version = device_string(id, CL_DEVICE_VERSION);
      info.driver_version = device_string(id, CL_DRIVER_VERSION);
      info.type = device_value<cl_device_type>(id, CL_DEVICE_TYPE);
      info.compute_units = device_value<cl_uint>(id, CL_DEVICE_MAX_COMPUTE_UNITS);
      info.global_memory = device_value<cl_ulong>(id, CL_DEVICE_GLOBAL_MEM_SIZE);
      info.max_buffer_bytes = device_value<cl_ulong>(id, CL_DEVICE_MAX_MEM_ALLOC_SIZE);
      info.correctly_rounded_divide_sqrt =
          (device_value<cl_device_fp_config>(id, CL_DEVICE_SINGLE_FP_CONFIG) &
           CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
      devices.push_back(info);
    }
  }
  return devices;
}

DeviceInfo select_device(const std::string& selector) { return select_device("", selector); }

DeviceInfo select_device(const std::string& platform_selector,
                         const std::string& device_selector) {
  const std::vector<DeviceInfo> all = enumerate_devices();
  if (all.empty()) {
    throw OpenClError(describe_failure("clGetPlatformIDs", "OpenCL ICD loader",
                                       kPlatformNotFoundKhr) +
                          " (install a driver, e.g. pocl-opencl-icd for the CPU)",
                      kPlatformNotFoundKhr);
  }
  const std::vector<DeviceInfo> devices = platform_devices(all, platform_selector);
  if (device_selector.empty()) {
    // A usable GPU, a usable device, then any GPU, any device (which the matcher
    // refuses with the reason).
    const cl_device_type preference[] = {CL_DEVICE_TYPE_GPU, CL_DEVICE_TYPE_ALL};
    for (bool need_exact : {true, false}) {
      for (cl_device_type type : preference) {
        for (const DeviceInfo& d : devices) {
          if ((d.type & type) && (d.correctly_rounded_divide_sqrt || !need_exact)) return d;
        }
      }
    }
    return devices.front();
  }
  if (all_digits(device_selector)) {
    // At most 9 digits, so that stoul cannot overflow; no machine has more devices.
    size_t index = device_selector.size() <= 9 ? std::stoul(device_selector) : devices.size();
    if (index < devices.size()) return devices[index];
  } else {
    for (const DeviceInfo& d : devices) {
      if (lower(d.platform_name + " " + d.name).find(lower(device_selector)) !=
          std::string::npos) {
        return d;
      }
    }
  }
  const std::string where =
      platform_selector.empty() ? "" : " on platform '" + devices.front().platform_name + "'";
  throw OpenClError("no OpenCL device" + where + " matches '" + device_selector +
                        "'; the devices are:" +
                        device_list(devices, !platform_selector.empty()),
                    CL_DEVICE_NOT_FOUND);
}

}  // namespace flexsight::opencl

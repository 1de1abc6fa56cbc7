#include "host/cli/backend.h"

#include "host/cli/arguments.h"
#include "host/io/input_error.h"

#if defined(FLEXSIGHT_HAVE_OPENCL)
#include "host/runtime/cl_program.h"
#endif

namespace flexsight {

BackendOptions take_backend_options(std::vector<std::string>& args) {
  BackendOptions options;
  const std::string device = take_option(args, "--device");
  if (device.empty() || device == "auto") {
    options.kind = BackendKind::Auto;
  } else if (device == "opencl") {
    options.kind = BackendKind::OpenCl;
  } else if (device == "reference") {
    options.kind = BackendKind::Reference;
  } else {
    throw InputError("option --device", "expected auto, opencl or reference, got '" + device + "'");
  }
  options.cl_platform = take_option(args, "--cl-platform");
  options.cl_device = take_option(args, "--cl-device");
  const auto reject_with_reference = [&options](const std::string& value, const char* option,
                                                 const char* what = "selects an OpenCL device") {
    if (options.kind == BackendKind::Reference && !value.empty()) {
      throw InputError(std::string("option ") + option,
                       std::string(what) + ", but --device reference runs no OpenCL");
    }
  };
  const std::string max_memory = take_option(args, "--cl-max-memory");
  if (!max_memory.empty()) {
    const std::optional<size_t> bytes = parse_byte_size(max_memory);
    if (!bytes) {
      throw InputError("option --cl-max-memory",
                       "expected a positive size such as 64M or 2G, got '" + max_memory + "'");
    }
    options.cl_max_memory = *bytes;
  }
  options.cl_build_options = take_option(args, "--cl-build-options");
#if defined(FLEXSIGHT_HAVE_OPENCL)
  const std::string inexact = opencl::inexact_build_option(options.cl_build_options);
  if (!inexact.empty()) throw InputError("option --cl-build-options", inexact);
#endif
  reject_with_reference(options.cl_platform, "--cl-platform");
  reject_with_reference(options.cl_device, "--cl-device");
  reject_with_reference(max_memory, "--cl-max-memory", "limits OpenCL device memory");
  reject_with_reference(options.cl_build_options, "--cl-build-options",
                        "builds the OpenCL kernels");
  return options;
}

std::optional<size_t> parse_byte_size(const std::string& text) {
  size_t digits = 0;
  while (digits < text.size() && text[digits] >= '0' && text[digits] <= '9') ++digits;
  if (digits == 0 || digits > 15) return std::nullopt;  // 15 digits: no overflow below
  const std::string suffix = text.substr(digits);
  int shift = 0;
  if (suffix.empty() || suffix == "B") {
    shift = 0;
  } else if (suffix == "K" || suffix == "KiB" || suffix == "KB") {
    shift = 10;
  } else if (suffix == "M" || suffix == "MiB" || suffix == "MB") {
    shift = 20;
  } else if (suffix == "G" || suffix == "GiB" || suffix == "GB") {
    shift = 30;
  } else {
    return std::nullopt;
  }
  const unsigned long long count = std::stoull(text.substr(0, digits));
  if (count == 0 || count > (~0ULL >> (shift + 1))) return std::nullopt;
  return static_cast<size_t>(count << shift);
}

std::string backend_options_help() {
  return "  --device auto|opencl|reference\n"
         "                              matcher backend; auto (default): OpenCL when a usable\n"
         "                              device exists, else the reference path (same bytes)\n"
         "  --cl-platform N|NAME        OpenCL platform: its number or part of its name\n"
         "                              (see 'flexsight devices')\n"
         "  --cl-device N|NAME          OpenCL device: its number (within --cl-platform when\n"
         "                              given) or part of its name\n"
         "  --cl-max-memory SIZE        most device memory a run may hold (e.g. 64M, 1G);\n"
         "                              a run that needs more fails under opencl, runs the\n"
         "                              reference path under auto\n"
         "  --cl-build-options \"OPTS\"    extra OpenCL C build options for every kernel, for\n"
         "                              tuning on a device (e.g. -cl-nv-maxrregcount=64);\n"
         "                              options that change the arithmetic are refused\n";
}

}  // namespace flexsight

// flexsight devices: what OpenCL sees, and which device the OpenCL path would take.
#include <cstdio>
#include <iostream>

#include "host/cli/arguments.h"
#include "host/cli/backend.h"
#include "host/cli/commands.h"
#include "host/io/input_error.h"
#include "host/runtime/opencl_device_rows.h"

namespace flexsight {
namespace {

void print_help() {
  std::cout << "usage: flexsight devices\n"
               "Lists every OpenCL platform and device: type, compute units, global memory, the\n"
               "largest single buffer (a run holds about 240 bytes per pixel of the left image at\n"
               "once, 83 MiB for 741x497: stereo --profile prints it, --cl-max-memory caps it)\n"
               "and whether it rounds single-precision divide and sqrt correctly (the OpenCL path\n"
               "needs that to give the reference path's bytes). Exit code 1 when there is none.\n";
}

std::string memory_text(unsigned long long bytes) {
  char text[32];
  const double mib = static_cast<double>(bytes) / (1024.0 * 1024.0);
  if (mib >= 1024.0) {
    std::snprintf(text, sizeof text, "%.1f GiB", mib / 1024.0);
  } else {
    std::snprintf(text, sizeof text, "%.0f MiB", mib);
  }
  return text;
}

}  // namespace

int run_devices_command(std::vector<std::string> args) {
  if (take_flag(args, "--help") || take_flag(args, "-h")) {
    print_help();
    return 0;
  }
  reject_unknown_options(args);
  if (!args.empty()) throw InputError("devices", "takes no arguments, got '" + args.front() + "'");

  std::string why;
  const std::vector<OpenClDeviceRow> rows = list_opencl_device_rows(&why);
  if (rows.empty()) throw InputError("OpenCL", why);
  std::printf("| # | platform | device | type | compute units | global memory | "
              "largest buffer | correctly rounded divide/sqrt |\n"
              "|---|---|---|---|---|---|---|---|\n");
  for (const OpenClDeviceRow& row : rows) {
    std::printf("| %d%s | %d: %s | %d: %s (%s) | %s | %u | %s | %s | %s |\n", row.index,
                row.is_default ? " (default)" : "", row.platform_index, row.platform.c_str(),
                row.index_in_platform, row.name.c_str(), row.version.c_str(), row.type.c_str(),
                row.compute_units, memory_text(row.global_memory).c_str(), memory_text(row.max_buffer_bytes).c_str(),
                row.correctly_rounded_divide_sqrt ? "yes" : "no (unusable)");
  }
  std::printf("\n--cl-platform takes the platform's number or part of its name; --cl-device the\n"
              "device's # (its number within the platform with --cl-platform) or part of its\n"
              "name. Without them the first GPU with correctly rounded divide/sqrt is used,\n"
              "else the first such device.\n");
  return 0;
}

}  // namespace flexsight

#include "host/runtime/cl_program.h"

#include <sstream>

namespace flexsight::opencl {
namespace {

std::string build_log(cl_program program, cl_device_id device) {
  size_t size = 0;
  if (clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size) !=
      CL_SUCCESS) {
    return "(no build log)";
  }
  std::string log(size, '\0');
  if (clGetProgramBuildInfo(program, device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr) !=
      CL_SUCCESS) {
    return "(no build log)";
  }
  return log.c_str();
}

ProgramHandle build(cl_context context, const DeviceInfo& device, const KernelSource& source,
                    const std::string& options) {
  cl_int status = CL_SUCCESS;
  const char* text = source.text;
  ProgramHandle program(clCreateProgramWithSource(context, 1, &text, nullptr, &status));
  check(status, "clCreateProgramWithSource", source.file);
  status = clBuildProgram(program.get(), 1, &device.device, options.c_str(), nullptr, nullptr);
  if (status != CL_SUCCESS) {
    throw OpenClError(describe_failure("clBuildProgram", device.name, status) + " (" +
                          source.file + ", options '" + options + "'); build log:\n" +
                          build_log(program.get(), device.device),
                      status);
  }
  return program;
}

}  // namespace

std::string inexact_build_option(const std::string& options) {
  static const char* const kChangesArithmetic[] = {
      "-cl-fast-relaxed-math",   "-cl-mad-enable",     "-cl-unsafe-math-optimizations",
      "-cl-finite-math-only",    "-cl-no-signed-zeros", "-cl-denorms-are-zero",
      "-cl-single-precision-constant", "-ffp-contract", "-ffast-math"};
  static const char* const kChangesSpecialisation[] = {"-D", "-U", "-I", "-cl-std"};
  std::istringstream words(options);
  std::string word;
  while (words >> word) {
    for (const char* bad : kChangesArithmetic) {
      if (word.rfind(bad, 0) == 0) {
        return "'" + word + "' changes the kernels' floating-point arithmetic, so the OpenCL "
               "path could no longer give the reference path's bytes";
      }
    }
    for (const char* bad : kChangesSpecialisation) {
      if (word.rfind(bad, 0) == 0) {
        return "'" + word + "' would override how the host specialises the kernels "
               "(their -D options and OpenCL C version)";
      }
    }
  }
  return {};
}

const char* const kExactBuildOptions = "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt";

cl_program ProgramCache::get(cl_context context, const DeviceInfo& device,
                             const KernelSource& source, const std::string& extra_options) {
  const std::string options =
      extra_options.empty() ? kExactBuildOptions : kExactBuildOptions + (" " + extra_options);
  Key key{device.device, source.hash, options};
  auto found = programs_.find(key);
  if (found != programs_.end()) return found->second.get();
  ProgramHandle program = build(context, device, source, options);
  cl_program raw = program.get();
  programs_.emplace(std::move(key), std::move(program));
  return raw;
}

}  // namespace flexsight::opencl

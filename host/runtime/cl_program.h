#pragma once
// Program builds, cached in memory by (device, source hash, build options): the stages
// ask for their program on every run, and a build costs from milliseconds (driver
// cache) to seconds.
#include <cstdint>
#include <map>
#include <string>
#include <tuple>

#include "host/runtime/cl_device.h"
#include "host/runtime/cl_handle.h"
#include "host/runtime/kernel_sources.h"

namespace flexsight::opencl {

// The options every kernel is built with, for bit-exact agreement with the reference:
// OpenCL 1.2 C and correctly rounded division and square root. Never -cl-mad-enable,
// -cl-fast-relaxed-math or -cl-denorms-are-zero; contraction is off in pms_math.h.
extern const char* const kExactBuildOptions;

// Why `options` (a user's extra build options, appended to every kernel's) would break
// the kernels' agreement with the reference, naming the offending option: fast or
// relaxed maths, contraction, flushed denormals, or -D/-U/-I/-cl-std, which would
// change the host's specialisation of the kernels. Empty when they are acceptable
// (e.g. NVIDIA's -cl-nv-maxrregcount=64, -cl-opt-disable).
std::string inexact_build_option(const std::string& options);

class ProgramCache {
 public:
  // The built program of `source` for `device` with kExactBuildOptions followed by
  // `extra_options` (e.g. "-DPMS_MEDIAN_MAX_SAMPLES=49"). Throws OpenClError with
  // the build log when the source does not compile. The program lives as long as the
  // cache.
  cl_program get(cl_context context, const DeviceInfo& device, const KernelSource& source,
                 const std::string& extra_options);
  size_t size() const { return programs_.size(); }

 private:
  using Key = std::tuple<cl_device_id, std::uint64_t, std::string>;
  std::map<Key, ProgramHandle> programs_;
};

}  // namespace flexsight::opencl

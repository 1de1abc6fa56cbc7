#pragma once
// An OpenCL source embedded at build time by cmake/embed_kernels.cmake, its headers
// inlined. Each module's sources are declared in the generated header
// generated/<module>_kernel_sources.h (cmake/kernel_module.cmake), in namespace
// kernel_sources::<module>.
#include <cstdint>

namespace flexsight::opencl {

struct KernelSource {
  const char* file;    // "propagate_view.cl", for messages
  std::uint64_t hash;  // of `text`: the program cache key with device and options
  const char* text;    // self-contained OpenCL C
};

}  // namespace flexsight::opencl

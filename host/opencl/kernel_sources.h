#pragma once
// The OpenCL sources of kernels/, embedded at build time by cmake/embed_kernels.cmake
// with their headers inlined (one generated .cpp per .cl, listed in
// host/opencl/CMakeLists.txt).
#include <cstdint>

namespace flexsight::opencl {

struct KernelSource {
  const char* file;    // "propagate_view.cl", for messages
  std::uint64_t hash;  // of `text`: the program cache key with device and options
  const char* text;    // self-contained OpenCL C
};

namespace kernel_sources {
extern const KernelSource build_view;
extern const KernelSource init_random_planes;
extern const KernelSource evaluate_costs;
extern const KernelSource propagate_spatial;
extern const KernelSource propagate_view;
extern const KernelSource refine_random;
extern const KernelSource carry_planes_to_finer;
extern const KernelSource plane_disparities;
extern const KernelSource lr_confidence;
extern const KernelSource list_unsure_pixels;
extern const KernelSource upsample_nearest;
extern const KernelSource left_right_check;
extern const KernelSource fill_inconsistent;
extern const KernelSource weighted_median;
extern const KernelSource small_segments;
}  // namespace kernel_sources

}  // namespace flexsight::opencl

// The detection module's kernel files: every .cl of kernels/detect/ is embedded, and
// each builds on its own, without any -D option.
#include <gtest/gtest.h>

#include <filesystem>
#include <iterator>
#include <set>
#include <string>

#include "generated/detect_kernel_sources.h"
#include "tests/detect/opencl/ssd_device_fixture.h"

namespace flexsight::opencl::ssd_test {
namespace {

TEST(DetectKernelFiles, EveryClFileOfTheDetectModuleIsEmbedded) {
  std::set<std::string> on_disk;
  for (const auto& entry : std::filesystem::directory_iterator(FLEXSIGHT_KERNEL_DIR "/detect")) {
    if (entry.path().extension() == ".cl") on_disk.insert(entry.path().filename().string());
  }
  std::set<std::string> embedded;
  for (const KernelSource* source : kernel_sources::detect::all) embedded.insert(source->file);
  EXPECT_EQ(on_disk, embedded)
      << "a kernel file that is not embedded: KERNELS in host/detect/CMakeLists.txt";
}

TEST(DetectKernelFiles, EachBuildsWithoutBuildOptions) {
  for (const KernelSource* source : kernel_sources::detect::all) {
    cl_program program = nullptr;
    ASSERT_NO_THROW(program = shared_context()->program(*source)) << source->file;
    cl_uint kernel_count = 0;
    ASSERT_EQ(clCreateKernelsInProgram(program, 0, nullptr, &kernel_count), CL_SUCCESS);
    EXPECT_GT(kernel_count, 0u) << source->file << " defines no kernel";
  }
}

}  // namespace
}  // namespace flexsight::opencl::ssd_test

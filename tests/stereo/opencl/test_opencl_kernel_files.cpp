// The kernel files themselves: every .cl of kernels/stereo/ is embedded, and each one builds
// on its own, without any -D option, because every macro it reads has a default. That
// keeps a file usable outside the scheduler (an offline compiler, a profiler, a bug
// report) and catches a macro that only the scheduler happened to define.
#include <gtest/gtest.h>

#include <filesystem>
#include <iterator>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "generated/stereo_kernel_sources.h"
#include "tests/stereo/opencl/opencl_test_support.h"

namespace flexsight::opencl {
// gtest prints a failing test's parameter; the file name says more than the pointer
// (found by argument-dependent lookup, hence this namespace).
void PrintTo(const KernelSource* source, std::ostream* out) { *out << source->file; }
}  // namespace flexsight::opencl

namespace flexsight::opencl::test {
namespace {

std::vector<const KernelSource*> all_kernel_sources() {
  return {std::begin(kernel_sources::stereo::all), std::end(kernel_sources::stereo::all)};
}

TEST(KernelFiles, EveryClFileOfTheStereoModuleIsEmbedded) {
  std::set<std::string> on_disk;
  for (const auto& entry : std::filesystem::directory_iterator(FLEXSIGHT_KERNEL_DIR "/stereo")) {
    if (entry.path().extension() == ".cl") on_disk.insert(entry.path().filename().string());
  }
  std::set<std::string> embedded;
  for (const KernelSource* source : all_kernel_sources()) embedded.insert(source->file);
  EXPECT_EQ(on_disk, embedded)
      << "a kernel file that is not embedded: KERNELS in host/stereo/CMakeLists.txt";
}

class KernelFileBuildsAlone : public ::testing::TestWithParam<const KernelSource*> {};

TEST_P(KernelFileBuildsAlone, WithoutBuildOptions) {
  const KernelSource& source = *GetParam();
  cl_program program = nullptr;
  ASSERT_NO_THROW(program = context().program(source)) << source.file;
  cl_uint kernel_count = 0;
  ASSERT_EQ(clCreateKernelsInProgram(program, 0, nullptr, &kernel_count), CL_SUCCESS);
  EXPECT_GT(kernel_count, 0u) << source.file << " defines no kernel";
}

std::string kernel_file_name(const ::testing::TestParamInfo<const KernelSource*>& info) {
  std::string name = info.param->file;
  return name.substr(0, name.find('.'));
}

INSTANTIATE_TEST_SUITE_P(EveryFile, KernelFileBuildsAlone,
                         ::testing::ValuesIn(all_kernel_sources()), kernel_file_name);

}  // namespace
}  // namespace flexsight::opencl::test

// The flexsight binary end to end on the OpenCL path: the devices listed, the bytes of
// the reference path reproduced, and a clear failure (or, under auto, the reference
// path) when the device runs out of memory, a kernel fails to build or an option asks
// for what the kernels do not have.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <string>

#include "host/io/pfm.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_support.h"

using namespace flexsight::cli_test_support;

TEST_F(Cli, DevicesListsWhatOpenClSees) {
  RunResult r = run_flexsight("devices", dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;  // PoCL is installed wherever the tests run
  EXPECT_NE(r.out.find("| compute units | global memory | largest buffer |"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("| 0 (default) | 0: "), std::string::npos) << r.out;
  EXPECT_TRUE(r.out.find("| CPU |") != std::string::npos ||
              r.out.find("| GPU |") != std::string::npos ||
              r.out.find("| accelerator |") != std::string::npos)
      << r.out;
}

TEST_F(Cli, OpenClAndReferenceWriteTheSameBytes) {
  const std::string pair = "stereo " + left_ + " " + right_ + " --ndisp 16" + quick();
  const std::string reference_pfm = (dir_ / "reference.pfm").string();
  const std::string opencl_pfm = (dir_ / "opencl.pfm").string();
  RunResult reference = run_flexsight(pair + " -o " + reference_pfm + " --device reference", dir_);
  ASSERT_EQ(reference.exit_code, 0) << reference.err;
  EXPECT_NE(reference.out.find("| stage (reference path) |"), std::string::npos) << reference.out;
  RunResult opencl = run_flexsight(pair + " -o " + opencl_pfm + " --device opencl", dir_);
  ASSERT_EQ(opencl.exit_code, 0) << opencl.err;
  EXPECT_NE(opencl.out.find("| stage (OpenCL path on #"), std::string::npos) << opencl.out;

  EXPECT_TRUE(flexsight::testing_support::same_bytes(flexsight::read_pfm(reference_pfm),
                                                    flexsight::read_pfm(opencl_pfm)));
}

// One pixel per work item, the GPU setting (FLEXSIGHT_CL_LANES=1), gives the bytes of
// the default 8 and of the reference.
TEST_F(Cli, OneLanePerWorkItemWritesTheReferenceBytes) {
  const std::string pair = "stereo " + left_ + " " + right_ + " --ndisp 16" + quick();
  const cv::Mat expected = reference_disparity(pair);
  const std::string one_lane_pfm = (dir_ / "one_lane.pfm").string();
  RunResult one_lane = run_flexsight(
      pair + " -o " + one_lane_pfm + " --device opencl", dir_, "FLEXSIGHT_CL_LANES=1 ");
  ASSERT_EQ(one_lane.exit_code, 0) << one_lane.err;
  EXPECT_TRUE(flexsight::testing_support::same_bytes(expected, flexsight::read_pfm(one_lane_pfm)));
}

// A device that runs out of memory, made reproducible by a device memory budget smaller
// than the run needs: under opencl a non-zero exit naming the device, the step and the
// buffer, and no output file; under auto the reference path's bytes, with a notice.
TEST_F(Cli, ARunOverTheDeviceMemoryBudgetFailsNamingDeviceStepAndBuffer) {
  const std::string pair = "stereo " + left_ + " " + right_ + " --ndisp 16" + quick();
  expect_rejected(pair + " -o " + output_ + " --device opencl --cl-max-memory 16K",
                  "--device opencl: running on #");
  RunResult r = run_flexsight(pair + " -o " + output_ + " --device opencl --cl-max-memory 16K",
                              dir_);
  EXPECT_NE(r.err.find(", pyramid: creating buffer '"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("over this run's device memory budget of 0.02 MiB"), std::string::npos)
      << r.err;
}

TEST_F(Cli, AutoRunsTheReferencePathWhenTheDeviceMemoryBudgetIsTooSmall) {
  const std::string pair = "stereo " + left_ + " " + right_ + " --ndisp 16" + quick();
  const cv::Mat expected = reference_disparity(pair);
  const std::string roomy_pfm = (dir_ / "roomy.pfm").string();
  RunResult fallback = run_flexsight(pair + " -o " + output_ + " --cl-max-memory 16K", dir_);
  ASSERT_EQ(fallback.exit_code, 0) << fallback.err;
  EXPECT_NE(fallback.err.find("note: --device auto: running on #"), std::string::npos)
      << fallback.err;
  EXPECT_NE(fallback.err.find("device memory budget of 0.02 MiB; running the reference path"),
            std::string::npos)
      << fallback.err;
  EXPECT_NE(fallback.out.find("| stage (reference path) |"), std::string::npos) << fallback.out;
  // A budget the run fits in changes nothing: the OpenCL path, the same bytes.
  RunResult roomy =
      run_flexsight(pair + " -o " + roomy_pfm + " --device opencl --cl-max-memory 64M", dir_);
  ASSERT_EQ(roomy.exit_code, 0) << roomy.err;
  EXPECT_NE(roomy.out.find("| stage (OpenCL path on #"), std::string::npos) << roomy.out;
  EXPECT_TRUE(flexsight::testing_support::same_bytes(expected, flexsight::read_pfm(output_)));
  EXPECT_TRUE(flexsight::testing_support::same_bytes(expected, flexsight::read_pfm(roomy_pfm)));
}

TEST_F(Cli, RejectsADeviceMemoryBudgetThatIsNotAPositiveSize) {
  for (const char* bad : {"0", "12X", "-5", "1.5G", "M", "99999999999999999G"}) {
    expect_rejected("stereo " + left_ + " " + right_ + " -o " + output_ + " --ndisp 16" +
                        " --cl-max-memory " + bad + quick(),
                    "option --cl-max-memory: expected a positive size such as 64M or 2G, got '" +
                        std::string(bad) + "'");
  }
  expect_rejected("stereo " + left_ + " " + right_ + " -o " + output_ +
                      " --ndisp 16 --device reference --cl-max-memory 1G" + quick(),
                  "option --cl-max-memory: limits OpenCL device memory, but --device reference");
}

// A device that fails to build a kernel, on PoCL: build options the compiler
// refuses make every kernel's build fail, as a driver's compiler bug would.
TEST_F(Cli, AKernelBuildFailureFailsUnderOpenClWithTheDeviceAndTheBuildLog) {
  const std::string run = "stereo " + left_ + " " + right_ + " -o " + output_ +
                          " --ndisp 16 --device opencl --cl-build-options -cl-no-such-option" +
                          quick();
  expect_rejected(run, "--device opencl: building the kernels on #0 ");
  RunResult r = run_flexsight(run, dir_);
  EXPECT_NE(r.err.find("clBuildProgram"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("-cl-no-such-option'); build log:\n"), std::string::npos) << r.err;
}

TEST_F(Cli, AutoRunsTheReferencePathWhenTheKernelsFailToBuild) {
  const std::string pair = "stereo " + left_ + " " + right_ + " --ndisp 16" + quick();
  const cv::Mat expected = reference_disparity(pair);
  RunResult fallback =
      run_flexsight(pair + " -o " + output_ + " --cl-build-options -cl-no-such-option", dir_);
  ASSERT_EQ(fallback.exit_code, 0) << fallback.err;
  EXPECT_NE(fallback.err.find("note: --device auto: building the kernels on #0 "),
            std::string::npos)
      << fallback.err;
  // One line: the build log is left to --device opencl.
  EXPECT_NE(fallback.err.find("(in full with --device opencl); running the reference path\n"),
            std::string::npos)
      << fallback.err;
  EXPECT_TRUE(flexsight::testing_support::same_bytes(expected, flexsight::read_pfm(output_)));
}

TEST_F(Cli, BuildOptionsThatKeepTheArithmeticKeepTheReferenceBytes) {
  const std::string pair = "stereo " + left_ + " " + right_ + " --ndisp 16" + quick();
  const cv::Mat expected = reference_disparity(pair);
  RunResult unoptimised = run_flexsight(
      pair + " -o " + output_ + " --device opencl --cl-build-options -cl-opt-disable", dir_);
  ASSERT_EQ(unoptimised.exit_code, 0) << unoptimised.err;
  EXPECT_TRUE(flexsight::testing_support::same_bytes(expected, flexsight::read_pfm(output_)));
}

TEST_F(Cli, RejectsBuildOptionsThatWouldChangeTheResults) {
  const std::string pair = "stereo " + left_ + " " + right_ + " -o " + output_ + " --ndisp 16";
  for (const char* bad : {"-cl-fast-relaxed-math", "-cl-mad-enable", "-cl-denorms-are-zero",
                          "-cl-unsafe-math-optimizations"}) {
    expect_rejected(pair + " --cl-build-options '-cl-opt-disable " + bad + "'" + quick(),
                    "option --cl-build-options: '" + std::string(bad) +
                        "' changes the kernels' floating-point arithmetic");
  }
  for (const char* bad : {"-DPMS_LANES=4", "-cl-std=CL2.0", "-UPMS_LANES"}) {
    expect_rejected(pair + " --cl-build-options " + bad + quick(),
                    "option --cl-build-options: '" + std::string(bad) +
                        "' would override how the host specialises the kernels");
  }
  expect_rejected(pair + " --device reference --cl-build-options -cl-opt-disable" + quick(),
                  "option --cl-build-options: builds the OpenCL kernels, but --device reference");
}

TEST_F(Cli, RejectsALaneCountTheKernelsDoNotHave) {
  RunResult r = run_flexsight("stereo " + left_ + " " + right_ + " -o " + output_ +
                                  " --ndisp 16 --device opencl" + quick(),
                              dir_, "FLEXSIGHT_CL_LANES=3 ");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("FLEXSIGHT_CL_LANES: must be 1, 4, 8 or 16, got '3'"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(output_));
}

TEST_F(Cli, RejectsAnUnknownDevice) {
  expect_rejected("stereo " + left_ + " " + right_ + " -o " + output_ + " --device bogus",
                  "--device");
}

TEST_F(Cli, RejectsAnOpenClDeviceThatDoesNotExist) {
  RunResult r = run_flexsight("stereo " + left_ + " " + right_ + " -o " + output_ +
                                  " --ndisp 16 --device opencl --cl-device 99" + quick(),
                              dir_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("--cl-device"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no OpenCL device matches '99'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(output_));
}

TEST_F(Cli, ProfilePrintsTheTimePerKernel) {
  RunResult r = run_flexsight("stereo " + left_ + " " + right_ + " -o " + output_ +
                                  " --ndisp 16 --device opencl --profile" + quick(),
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("| kernel | calls | total ms | mean ms |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("| propagate_spatial | "), std::string::npos) << r.out;
}

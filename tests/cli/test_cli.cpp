// The flexsight binary end to end: bad input gives a clear message naming the file or
// option and a non-zero exit, and never leaves an output file behind.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "host/io/pfm.h"
#include "tests/common/test_support.h"

namespace fs = std::filesystem;
using flexsight::testing_support::fresh_temp_dir;

namespace {

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// `environment`: "NAME=value " assignments put before the command (empty: none).
RunResult run_flexsight(const std::string& arguments, const fs::path& dir,
                        const std::string& environment = "") {
  const std::string command = environment + std::string(FLEXSIGHT_BINARY) + " " + arguments + " > " +
                              (dir / "stdout.txt").string() + " 2> " + (dir / "stderr.txt").string();
  int status = std::system(command.c_str());
  RunResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(dir / "stdout.txt");
  result.err = slurp(dir / "stderr.txt");
  return result;
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    left_ = (dir_ / "left.png").string();
    right_ = (dir_ / "right.png").string();
    cv::imwrite(left_, flexsight::testing_support::random_rgb8(64, 48, 1));
    cv::imwrite(right_, flexsight::testing_support::random_rgb8(64, 48, 2));
    output_ = (dir_ / "disp.pfm").string();
  }
  // A failed test keeps its folder for inspection; a passing one leaves nothing behind.
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(dir_);
  }
  // Runs a command that must fail; checks exit code, message and that no output exists.
  void expect_rejected(const std::string& arguments, const std::string& must_mention) {
    RunResult r = run_flexsight(arguments, dir_);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(must_mention), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(output_));
    for (const auto& entry : fs::directory_iterator(dir_)) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
          << "left behind: " << entry.path();
    }
  }
  std::string quick() const {
    return " --window 7 --iterations 1 --iterations-coarsest 1 --iterations-fine 1 --quiet";
  }
  // The reference path's disparity for `pair` ("stereo LEFT RIGHT <options>"), the bytes
  // every other backend must reproduce; empty (and a failure) when the run fails.
  cv::Mat reference_disparity(const std::string& pair) {
    const std::string path = (dir_ / "reference.pfm").string();
    RunResult reference = run_flexsight(pair + " -o " + path + " --device reference", dir_);
    if (reference.exit_code != 0) {
      ADD_FAILURE() << reference.err;
      return cv::Mat();
    }
    return flexsight::read_pfm(path);
  }
  fs::path dir_;
  std::string left_, right_, output_;
};

}  // namespace

TEST_F(Cli, MatchesAPairAndWritesPfmAndPng) {
  const std::string png = (dir_ / "disp.png").string();
  RunResult r = run_flexsight("stereo " + left_ + " " + right_ + " -o " + output_ + " --png " +
                                  png + " --ndisp 16" + quick(),
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cv::Mat disparity = flexsight::read_pfm(output_);
  EXPECT_EQ(disparity.size(), cv::Size(64, 48));
  EXPECT_EQ(cv::imread(png).size(), cv::Size(64, 48));
  EXPECT_NE(r.out.find("| total |"), std::string::npos);  // time per stage
}

TEST_F(Cli, SceneFolderReadsNdispFromCalibAndScoresAgainstGroundTruth) {
  RunResult r = run_flexsight("stereo " + flexsight::testing_support::fixture_dir() + " -o " +
                                  output_ +
                                  " --window 11 --iterations 1 --iterations-coarsest 1 "
                                  "--iterations-fine 1",
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("ndisp 32 from calib.txt"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("| nonocc |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("confidence: sparsification AUC "), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("level 0"), std::string::npos) << "progress is shown";
}

// --help is a request (usage on stdout, exit 0); a command without arguments is a
// usage error (exit 1), for every command.
TEST_F(Cli, HelpExitsZeroAndNoArgumentsExitsOne) {
  for (const std::string command : {"stereo", "eval", "cloud", "render"}) {
    const RunResult help = run_flexsight(command + " --help", dir_);
    EXPECT_EQ(help.exit_code, 0) << command;
    EXPECT_NE(help.out.find("usage: flexsight " + command), std::string::npos)
        << command << ": " << help.out;
    const RunResult bare = run_flexsight(command, dir_);
    EXPECT_NE(bare.exit_code, 0) << command;
  }
  EXPECT_EQ(run_flexsight("devices --help", dir_).exit_code, 0);
}

TEST_F(Cli, RejectsAMissingImage) {
  const std::string missing = (dir_ / "nope.png").string();
  expect_rejected("stereo " + missing + " " + right_ + " -o " + output_, missing);
}

TEST_F(Cli, RejectsACorruptImage) {
  std::ofstream(dir_ / "corrupt.png") << "this is not a png";
  const std::string corrupt = (dir_ / "corrupt.png").string();
  expect_rejected("stereo " + left_ + " " + corrupt + " -o " + output_, corrupt);
}

TEST_F(Cli, RejectsAnEmptyImageFile) {
  std::ofstream(dir_ / "empty.png").close();
  const std::string empty = (dir_ / "empty.png").string();
  expect_rejected("stereo " + empty + " " + right_ + " -o " + output_, empty);
}

TEST_F(Cli, RejectsMismatchedSizes) {
  const std::string small = (dir_ / "small.png").string();
  cv::imwrite(small, flexsight::testing_support::random_rgb8(60, 48, 3));
  expect_rejected("stereo " + left_ + " " + small + " -o " + output_, small);
}

TEST_F(Cli, RejectsAnUnsupportedBitDepth) {
  const std::string floats = (dir_ / "float.tiff").string();
  cv::imwrite(floats, cv::Mat(48, 64, CV_32FC1, cv::Scalar(0.5)));
  expect_rejected("stereo " + left_ + " " + floats + " -o " + output_, floats);
}

TEST_F(Cli, RejectsImpossibleParameters) {
  const std::string pair = "stereo " + left_ + " " + right_ + " -o " + output_;
  expect_rejected(pair + " --ndisp 0", "--ndisp");
  expect_rejected(pair + " --ndisp -5", "--ndisp");
  expect_rejected(pair + " --ndisp 65", "--ndisp");  // wider than the 64-px image
  expect_rejected(pair + " --window 8", "--window");
  expect_rejected(pair + " --window-step-fine 0", "--window-step-fine");
  expect_rejected(pair + " --window 7 --window-step-fine 9", "--window-step-fine");
  expect_rejected(pair + " --alpha 1.5", "--alpha");
  expect_rejected(pair + " --confident-spatial-candidates 17", "--confident-spatial-candidates");
  expect_rejected(pair + " --confident-spatial-candidates -1", "--confident-spatial-candidates");
  expect_rejected(pair + " --refresh-confidence 2", "--refresh-confidence");
  expect_rejected(pair + " --speckle-size -1", "--speckle-size");
  expect_rejected(pair + " --raw-speckle-size -3", "--raw-speckle-size");
  expect_rejected(pair + " --refill-iterations 11", "--refill-iterations");
  expect_rejected(pair + " --refill-unsure-only 2", "--refill-unsure-only");
  expect_rejected(pair + " --iterations-fine 51", "--iterations-fine");
  expect_rejected(pair + " --iterations-finest -1", "--iterations-finest");
  expect_rejected(pair + " --window-step-finest -1", "--window-step-finest");
  expect_rejected(pair + " --window 7 --window-step-finest 9", "--window-step-finest");
  expect_rejected(pair + " --speckle-range inf", "--speckle-range");
  expect_rejected(pair + " --ndisp twelve", "--ndisp");
  expect_rejected(pair + " --preset quick", "--preset");
  expect_rejected(pair + " --preset fast --preset accurate", "--preset");
}

TEST_F(Cli, RejectsUnknownOptionsAndCommands) {
  expect_rejected("stereo " + left_ + " " + right_ + " -o " + output_ + " --bogus 3", "--bogus");
  RunResult r = run_flexsight("frobnicate", dir_);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("frobnicate"), std::string::npos);
}

TEST_F(Cli, RejectsAnOutputInAMissingFolderWithoutLeavingFiles) {
  const std::string bad_output = (dir_ / "no_such_dir" / "disp.pfm").string();
  RunResult r = run_flexsight("stereo " + left_ + " " + right_ + " -o " + bad_output +
                                  " --ndisp 16" + quick(),
                              dir_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(bad_output), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "no_such_dir"));
}

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

// Issue 3's out-of-memory case, made reproducible by a device memory budget smaller
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

// Issue 3's "a device that fails to build a kernel", on PoCL: build options the compiler
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

TEST_F(Cli, WritesBothViewsRawDisparities) {
  // The right image is the left one moved 4 px to the left: both views see disparity 4.
  const cv::Mat left = flexsight::testing_support::random_rgb8(64, 48, 1);
  cv::Mat right = flexsight::testing_support::random_rgb8(64, 48, 2);
  left.colRange(4, 64).copyTo(right.colRange(0, 60));
  cv::imwrite(left_, left);
  cv::imwrite(right_, right);
  const std::string raw_left = (dir_ / "raw_left.pfm").string();
  const std::string raw_right = (dir_ / "raw_right.pfm").string();
  RunResult r = run_flexsight("stereo " + left_ + " " + right_ + " -o " + output_ + " --raw " +
                                  raw_left + " --raw-right " + raw_right +
                                  " --ndisp 16 --window 7 --quiet --device reference",
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat views[2] = {flexsight::read_pfm(raw_left), flexsight::read_pfm(raw_right)};
  for (const cv::Mat& raw : views) {
    ASSERT_EQ(raw.size(), cv::Size(64, 48));
    int near_four = 0;
    for (int y = 4; y < 44; ++y) {
      for (int x = 8; x < 56; ++x) near_four += std::fabs(raw.at<float>(y, x) - 4.0f) <= 0.5f;
    }
    EXPECT_GT(near_four, 40 * 48 * 9 / 10);
  }
  // The two files are the two views, not one view twice: at the borders that only one
  // view can match (the left image's first columns, the right's last), they differ.
  EXPECT_GT(cv::norm(views[0], views[1], cv::NORM_L1), 0.0);
}

TEST_F(Cli, RejectsASecondOutputInAMissingFolderBeforeMatching) {
  const std::string bad_raw = (dir_ / "no_such_dir" / "raw_right.pfm").string();
  RunResult r = run_flexsight("stereo " + left_ + " " + right_ + " -o " + output_ +
                                  " --raw-right " + bad_raw + " --ndisp 16" + quick(),
                              dir_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find(bad_raw), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(output_));  // nothing written: the check comes first
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

// ------------------------------------------------------------------- 3D outputs --

TEST_F(Cli, StereoWritesDepthCloudConfidenceAndPictures) {
  const std::string scene = flexsight::testing_support::fixture_dir();
  const std::string ply = (dir_ / "cloud.ply").string(), depth = (dir_ / "depth.pfm").string(),
                    conf = (dir_ / "conf.pfm").string(), planes = (dir_ / "planes.pfm").string();
  RunResult r = run_flexsight("stereo " + scene + " -o " + output_ + " --ply " + ply +
                                  " --depth " + depth + " --conf " + conf + " --conf-png " +
                                  (dir_ / "conf.png").string() + " --planes " + planes +
                                  " --render " + (dir_ / "view.png").string() + quick(),
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat disparity = flexsight::read_pfm(output_);
  const cv::Mat z = flexsight::read_pfm(depth);
  ASSERT_EQ(z.size(), disparity.size());
  for (int y = 0; y < z.rows; y += 17) {
    for (int x = 0; x < z.cols; x += 13) {  // TeddyH calib: f 750, baseline 80 mm, doffs 26
      const float d = disparity.at<float>(y, x);
      EXPECT_NEAR(z.at<float>(y, x), 80.0 * 750.0 / (d + 26.0), 1e-3);
    }
  }
  EXPECT_EQ(flexsight::read_pfm(planes).channels(), 3);
  const cv::Mat c = flexsight::read_pfm(conf);
  double low, high;
  cv::minMaxLoc(c, &low, &high);
  EXPECT_GE(low, 0.0);
  EXPECT_LE(high, 1.0);
  EXPECT_FALSE(cv::imread((dir_ / "conf.png").string()).empty());
  EXPECT_FALSE(cv::imread((dir_ / "view.png").string()).empty());
  const std::string header = slurp(ply).substr(0, 400);
  EXPECT_NE(header.find("element vertex " + std::to_string(disparity.total())), std::string::npos)
      << header;  // dense result: every pixel becomes a point
  EXPECT_NE(header.find("property float confidence"), std::string::npos);
}

TEST_F(Cli, StereoRejectsACloudWithoutCalibrationBeforeMatching) {
  expect_rejected("stereo " + left_ + " " + right_ + " -o " + output_ + " --ndisp 16 --ply " +
                      (dir_ / "c.ply").string() + quick(),
                  "--calib");
}

TEST_F(Cli, CloudRejectsBadCompanionsAndOptions) {
  const std::string scene = flexsight::testing_support::fixture_dir();
  const std::string gt = scene + "/disp0GT.pfm", left = scene + "/im0.png";
  const std::string calib = scene + "/calib.txt";
  output_ = (dir_ / "cloud.ply").string();
  expect_rejected("cloud " + gt + " " + left + " -o " + output_, "--calib");
  const std::string missing = (dir_ / "nope.txt").string();
  expect_rejected("cloud " + gt + " " + left + " --calib " + missing + " -o " + output_, missing);
  const std::string small = (dir_ / "small.pfm").string();
  flexsight::write_pfm(small, cv::Mat(4, 4, CV_32FC3, cv::Scalar::all(0)));
  expect_rejected("cloud " + gt + " " + left + " --calib " + calib + " --planes " + small +
                      " -o " + output_,
                  small);
  expect_rejected("cloud " + gt + " " + left_ + " --calib " + calib + " -o " + output_, left_);
  expect_rejected("cloud " + gt + " " + left + " --calib " + calib + " --min-confidence 2 -o " +
                      output_,
                  "--min-confidence");
  expect_rejected("cloud " + gt + " " + left + " --calib " + calib +
                      " --min-depth 900 --max-depth 800 -o " + output_,
                  "--max-depth");
  expect_rejected("cloud " + gt + " " + left + " --calib " + calib + " --min-confidence 0.5 -o " +
                      output_,
                  "--min-confidence");
}

TEST_F(Cli, CloudFiltersByDepthRange) {
  const std::string scene = flexsight::testing_support::fixture_dir();
  const std::string all = (dir_ / "all.ply").string(), near = (dir_ / "near.ply").string();
  const std::string common = "cloud " + scene + "/disp0GT.pfm " + scene + "/im0.png --calib " +
                             scene + "/calib.txt --ply-ascii -o ";
  ASSERT_EQ(run_flexsight(common + all, dir_).exit_code, 0);
  ASSERT_EQ(run_flexsight(common + near + " --max-depth 1200", dir_).exit_code, 0);
  auto depths = [](const std::string& path) {
    std::istringstream in(slurp(path));
    std::string line;
    while (std::getline(in, line) && line != "end_header") {
    }
    std::vector<float> z;
    for (float x, y, zz; in >> x >> y >> zz && std::getline(in, line);) z.push_back(zz);
    return z;
  };
  const std::vector<float> every = depths(all), kept = depths(near);
  ASSERT_GT(kept.size(), 0u);
  EXPECT_LT(kept.size(), every.size());
  size_t expected = 0;
  for (float z : every) expected += z <= 1200;
  EXPECT_EQ(kept.size(), expected);
  for (float z : kept) EXPECT_LE(z, 1200);
}

// ------------------------------------------------------------- OpenCV's matchers --

TEST_F(Cli, OpenCvPeersRunThroughTheSameCommand) {
  const std::string scene = flexsight::testing_support::fixture_dir();
  for (const char* method : {"sgbm", "bm"}) {
    RunResult r = run_flexsight("stereo " + scene + " -o " + output_ + " --method " + method, dir_);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("| nonocc |"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("confidence:"), std::string::npos) << "OpenCV has no confidence";
    // OpenCV leaves pixels without a result (at least its left border): +inf in the PFM.
    const cv::Mat disparity = flexsight::read_pfm(output_);
    int missing = 0;
    for (int y = 0; y < disparity.rows; ++y) missing += !std::isfinite(disparity.at<float>(y, 0));
    EXPECT_EQ(missing, disparity.rows) << method;
    fs::remove(output_);
  }
  expect_rejected("stereo " + scene + " -o " + output_ + " --method sgbm --conf " +
                      (dir_ / "c.pfm").string(),
                  "disparity only");
}

// flexsight render: the fixture cube at 200 mm in front of its floor. The picture, the
// depth and the mask agree with the scene: the cube in the middle, nearer than its
// centre by at most half its diagonal, the floor at 200 mm + 1.1 x the cube's diagonal / 2.
TEST_F(Cli, RenderWritesPictureDepthAndMask) {
  const std::string cube = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/render/cube.obj";
  const std::string picture = (dir_ / "cube.png").string();
  const std::string depth = (dir_ / "cube_depth.pfm").string();
  const std::string mask = (dir_ / "cube_mask.png").string();
  RunResult r = run_flexsight("render " + cube + " -o " + picture + " --depth " + depth +
                                  " --mask " + mask + " --size 81x61 --focal 100 --distance 200" +
                                  " --light-radius 10 --shadow-samples 2 --threads 2",
                              dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat rgb = cv::imread(picture, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(rgb.type(), CV_8UC3);
  EXPECT_EQ(rgb.size(), cv::Size(81, 61));
  const cv::Mat z = flexsight::read_pfm(depth);
  const cv::Mat ids = cv::imread(mask, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(ids.type(), CV_8UC1);
  ASSERT_EQ(z.size(), ids.size());
  EXPECT_EQ(ids.at<std::uint8_t>(30, 40), 1);
  EXPECT_EQ(ids.at<std::uint8_t>(0, 0), 0);
  const float half_diagonal = 10.0f * std::sqrt(3.0f);
  int cube_pixels = 0;
  for (int y = 0; y < z.rows; ++y) {
    for (int x = 0; x < z.cols; ++x) {
      const float d = z.at<float>(y, x);
      if (ids.at<std::uint8_t>(y, x) == 1) {
        ++cube_pixels;
        EXPECT_GE(d, 200.0f - half_diagonal - 1e-3f);
        EXPECT_LE(d, 200.0f + half_diagonal);
      } else {
        EXPECT_NEAR(d, 200.0f + 1.1f * half_diagonal, 1e-3f);
      }
    }
  }
  // The cube spans about 20 to 35 mm across at 200 mm: 10 to 17 pixels at focal 100.
  EXPECT_GT(cube_pixels, 100);
  EXPECT_LT(cube_pixels, 17 * 17);
  // The same command again gives the same bytes.
  const std::string again = (dir_ / "again.png").string();
  ASSERT_EQ(run_flexsight("render " + cube + " -o " + again +
                              " --size 81x61 --focal 100 --distance 200 --light-radius 10" +
                              " --shadow-samples 2 --threads 1",
                          dir_)
                .exit_code,
            0);
  EXPECT_TRUE(flexsight::testing_support::same_bytes(rgb, cv::imread(again, cv::IMREAD_UNCHANGED)));
}

TEST_F(Cli, RenderRejectsBadMeshesAndOptionsWithoutWriting) {
  const std::string cube = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/render/cube.obj";
  const std::string empty = std::string(FLEXSIGHT_TEST_DATA_DIR) + "/render/empty.stl";
  const std::string missing = (dir_ / "missing.stl").string();
  const std::string picture = (dir_ / "picture.png").string();
  const std::pair<std::string, std::string> cases[] = {
      {"render " + missing + " -o " + picture, missing},
      {"render " + empty + " -o " + picture, empty + ": is empty"},
      {"render " + cube + " " + missing + " -o " + picture, missing},
      {"render " + cube + " -o " + picture + " --size 0x10", "option --size"},
      {"render " + cube + " -o " + picture + " --rotation 1,2", "option --rotation"},
      {"render " + cube + " -o " + picture + " --light-radius -1", "option --light-radius"},
      {"render " + cube + " -o " + picture + " --focal -5", "camera"},
      {"render " + cube + " -o " + picture + " --frobnicate 1", "--frobnicate"},
      {"render " + cube, "option -o"},
      {"render " + cube + " -o " + (dir_ / "no_folder" / "p.png").string(), "folder does not exist"},
  };
  for (const auto& [arguments, mention] : cases) {
    RunResult r = run_flexsight(arguments, dir_);
    EXPECT_EQ(r.exit_code, 1) << arguments << ": " << r.err;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << arguments << ": " << r.err;
    EXPECT_FALSE(fs::exists(picture)) << arguments;
  }
}

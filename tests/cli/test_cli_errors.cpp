// The flexsight binary end to end, bad input: a clear message naming the file or
// option and a non-zero exit, and never an output file left behind.
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "host/io/pfm.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_support.h"

using namespace flexsight::cli_test_support;

// --help is a request (usage on stdout, exit 0); a command without arguments is a
// usage error (exit 1), for every command.
TEST_F(Cli, HelpExitsZeroAndNoArgumentsExitsOne) {
  for (const std::string command : {"stereo", "eval", "eval-det", "cloud", "render"}) {
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

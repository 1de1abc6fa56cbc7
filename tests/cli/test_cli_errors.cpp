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
  expect_rejected(pair + " --census-shape 4x5", "--census-shape");   // even side
  expect_rejected(pair + " --census-shape 1x27", "--census-shape");  // 26 bits
  expect_rejected(pair + " --census-shape 5by5", "--census-shape");  // not ROWSxCOLS
  expect_rejected(pair + " --window-rows 6", "--window-rows");
  expect_rejected(pair + " --confident-spatial-candidates -1", "--confident-spatial-candidates");
  expect_rejected(pair + " --refresh-confidence 2", "--refresh-confidence");
  expect_rejected(pair + " --speckle-slopes yes", "--speckle-slopes");
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

// ---- Bad input at the edges of each option's type and range ----------------------

// Integer options are read into their own type: values beyond it are refused, not
// wrapped modulo 2^32 (--ndisp 4294967312 would run as ndisp 16).
TEST_F(Cli, IntegerOptionsBeyondTheirTypeAreRejectedNotWrapped) {
  const std::string pair = "stereo " + left_ + " " + right_ + " -o " + output_;
  for (const std::string option :
       {"--ndisp 4294967312", "--ndisp -4294967280", "--threads 4294967297", "--median-window 4294967299",
        "--speckle-size 4294967296", "--iterations-fine 4294967297", "--ndisp 99999999999",
        "--seed 4294967296", "--seed -1"}) {
    const std::string name = option.substr(0, option.find(' '));
    expect_rejected(pair + " " + option, name);
  }
  const RunResult r = run_flexsight(pair + " --ndisp 99999999999", dir_);
  EXPECT_NE(r.err.find("'99999999999'"), std::string::npos) << r.err;  // the value given, not a wrapped one
}

// NaN is never a value; infinity only where it has a documented meaning.
TEST_F(Cli, NotANumberAndInfinityAreRejectedWhereTheyMeanNothing) {
  const std::string pair = "stereo " + left_ + " " + right_ + " -o " + output_;
  for (const std::string option : {"--min-depth nan", "--max-depth nan", "--min-depth inf", "--max-depth -inf",
                                   "--min-confidence nan", "--alpha nan", "--gamma inf", "--gamma-distance nan"}) {
    expect_rejected(pair + " " + option, option.substr(0, option.find(' ')));
  }
  // Documented: --gamma-distance inf turns the distance term off.
  const RunResult off = run_flexsight(pair + " --ndisp 16 --gamma-distance inf" + quick(), dir_);
  EXPECT_EQ(off.exit_code, 0) << off.err;
}

// OpenCV's matchers assert or fail inside on images too small for them; the sizes are
// checked first, in our words.
TEST_F(Cli, OpenCvMatchersRejectImagesTooSmallForThem) {
  auto pair_of = [&](int width, int height) {
    const std::string name = std::to_string(width) + "x" + std::to_string(height);
    const std::string left = (dir_ / ("l" + name + ".png")).string();
    const std::string right = (dir_ / ("r" + name + ".png")).string();
    cv::imwrite(left, flexsight::testing_support::random_rgb8(width, height, 1));
    cv::imwrite(right, flexsight::testing_support::random_rgb8(width, height, 2));
    return "stereo " + left + " " + right + " -o " + output_ + " --ndisp 2";
  };
  // SGBM: wider than ndisp rounded up to 16 (it aborted at 1-12 px, failed at 16).
  for (const int width : {5, 12, 16}) {
    expect_rejected(pair_of(width, 8) + " --method sgbm", "opencv-sgbm needs images wider than");
  }
  // BM: its 9 x 9 block plus one each way (an internal error about SADWindowSize).
  for (const auto& [width, height] : {std::pair{5, 5}, std::pair{64, 9}, std::pair{9, 64}}) {
    expect_rejected(pair_of(width, height) + " --method bm", "opencv-bm needs images of at least 10 x 10");
  }
  // Just large enough: both run.
  for (const char* method : {"sgbm", "bm"}) {
    const RunResult r = run_flexsight(pair_of(17, 10) + " --method " + method, dir_);
    EXPECT_EQ(r.exit_code, 0) << method << ": " << r.err;
    fs::remove(output_);
  }
}

// --gt is read and checked before matching, so a bad one fails before -o writes over
// the file that is there.
TEST_F(Cli, ABadGroundTruthFailsBeforeAnyOutputIsWritten) {
  const std::string existing = "the disparity that was here";
  std::ofstream(output_) << existing;
  const std::string wrong_size = (dir_ / "gt_small.pfm").string();
  flexsight::write_pfm(wrong_size, cv::Mat(10, 10, CV_32FC1, cv::Scalar(3)));
  const std::string bad_header = (dir_ / "gt_bad.pfm").string();
  std::ofstream(bad_header) << "Pf\n64 48 7\n-1\n";
  const std::string png = (dir_ / "disp.png").string();
  for (const std::string& gt : {wrong_size, bad_header}) {
    const RunResult r = run_flexsight("stereo " + left_ + " " + right_ + " -o " + output_ + " --png " + png +
                                          " --ndisp 16 --gt " + gt + quick(),
                                      dir_);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find(gt), std::string::npos) << r.err;
    EXPECT_EQ(slurp(output_), existing);
    EXPECT_FALSE(fs::exists(png));
  }
  fs::remove(output_);
  expect_rejected("stereo " + left_ + " " + right_ + " -o " + output_ + " --gt-mask " + png, "--gt-mask");
}

// An empty or malformed scene selection ran every scene.
TEST_F(Cli, AnEmptySceneSelectionIsAnError) {
  for (const std::string selection : {"','", "''", "'A,,B'", "'A,'"}) {
    expect_rejected("eval " + dir_.string() + " --scenes " + selection, "--scenes");
  }
}

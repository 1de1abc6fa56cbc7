#pragma once
// The `Cli` fixture of the tests of the flexsight binary (tests/cli/test_cli_*.cpp): a
// fresh folder per test with a random stereo pair in it, the binary run with its output
// captured, and the check that a rejected command fails cleanly.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

#include "host/io/pfm.h"
#include "tests/common/test_support.h"

namespace flexsight::cli_test_support {

namespace fs = std::filesystem;
using flexsight::testing_support::fresh_temp_dir;

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every file under `dir` with its bytes (folders as "<folder>"): compared before and
// after a run that must leave a folder as it was.
inline std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(entry.path(), dir).string();
    files[name] = entry.is_regular_file() ? slurp(entry.path()) : "<folder>";
  }
  return files;
}

// `environment`: "NAME=value " assignments put before the command (empty: none).
inline RunResult run_flexsight(const std::string& arguments, const fs::path& dir,
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

}  // namespace flexsight::cli_test_support

// The flexsight binary end to end, runs that succeed: a pair and a scene folder matched,
// both views' raw disparities, the 3D outputs (depth, cloud, confidence, pictures) and
// the cloud command, and OpenCV's matchers through the same command.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "host/io/pfm.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/test_support.h"

using namespace flexsight::cli_test_support;

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

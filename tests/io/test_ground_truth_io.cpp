// Tests of the ground-truth formats: KITTI's 16-bit disparity PNGs
// (host/io/kitti_disparity.h) and Middlebury v2's 8-bit disparities and masks
// (host/io/middlebury_v2.h).
//
// The tests that check a format on synthetic files also read the real files of that
// format, from the datasets folder of tests/common/real_datasets.h; a missing real file
// fails them.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "host/io/image_io.h"
#include "host/io/kitti_disparity.h"
#include "host/io/middlebury_v2.h"
#include "tests/io/io_test_support.h"

using namespace flexsight::io_test_support;

// ------------------------------------------------------------------------ KITTI --

TEST(KittiDisparity, RoundTrip) {
  ScratchDir dir;
  const std::string path = dir.file("000000_10.png");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const cv::Mat disparity =
      (cv::Mat_<float>(2, 4) << 12.5f, 0.0f, kInf, -3.0f, 300.0f, 0.001f, 7.0f / 256, nan);
  flexsight::write_kitti_disparity(path, disparity);

  // round(d * 256), valid values clamped to 1..65535, invalid ones 0.
  const cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(raw.type(), CV_16UC1);
  const cv::Mat expected_raw = (cv::Mat_<std::uint16_t>(2, 4) << 3200, 1, 0, 0, 65535, 1, 7, 0);
  EXPECT_EQ(cv::countNonZero(raw != expected_raw), 0) << raw;

  const cv::Mat loaded = flexsight::read_kitti_disparity(path);
  ASSERT_EQ(loaded.type(), CV_32FC1);
  const std::vector<float> expected = {12.5f,          1.0f / 256, kInf,       kInf,
                                       65535.0f / 256, 1.0f / 256, 7.0f / 256, kInf};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(loaded.at<float>(i / 4, i % 4), expected[i]) << i;
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"000000_10.png"});
}

TEST(KittiDisparity, ReadsKittiGroundTruth) {
  // A 16-bit PNG written by OpenCV directly, as KITTI's devkit would.
  ScratchDir dir;
  const std::string path = dir.file("disp_noc.png");
  const cv::Mat raw = (cv::Mat_<std::uint16_t>(1, 3) << 0, 256, 65535);
  ASSERT_TRUE(cv::imwrite(path, raw));
  const cv::Mat disparity = flexsight::read_kitti_disparity(path);
  EXPECT_EQ(disparity.at<float>(0, 0), kInf);
  EXPECT_EQ(disparity.at<float>(0, 1), 1.0f);
  EXPECT_EQ(disparity.at<float>(0, 2), 65535.0f / 256);

  const fs::path real = real_datasets_dir() / "KITTI2012/training/disp_noc/000070_10.png";
  ASSERT_TRUE(real_data_present(real));
  const cv::Mat gt = flexsight::read_kitti_disparity(real.string());
  EXPECT_EQ(gt.size(), cv::Size(1241, 376));
  EXPECT_GT(count_inf(gt), 0);  // sparse LiDAR
  EXPECT_LT(count_inf(gt), gt.rows * gt.cols);
  EXPECT_TRUE(finite_values_within(gt, 256));
}

TEST(KittiDisparity, RejectsWrongPngKinds) {
  ScratchDir dir;
  const std::string gray8 = dir.file("gray8.png");
  ASSERT_TRUE(cv::imwrite(gray8, cv::Mat(2, 2, CV_8UC1, cv::Scalar(10))));
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_kitti_disparity(gray8); }, gray8,
                                 "single-channel 16-bit PNG"));
  const std::string color16 = dir.file("color16.png");
  ASSERT_TRUE(cv::imwrite(color16, cv::Mat(2, 2, CV_16UC3, cv::Scalar(10, 10, 10))));
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_kitti_disparity(color16); }, color16,
                                 "single-channel 16-bit PNG"));
  const std::string text = dir.file("text.png");
  write_bytes(text, "not a png at all");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_kitti_disparity(text); }, text,
                                 "is not a PNG file"));
  const std::string missing = dir.file("missing.png");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_kitti_disparity(missing); }, missing,
                                 "does not exist"));
}

TEST(KittiDisparity, WriteRejectsNonFloatImage) {
  ScratchDir dir;
  const std::string path = dir.file("out.png");
  EXPECT_TRUE(throws_input_error(
      [&] { flexsight::write_kitti_disparity(path, cv::Mat(2, 2, CV_16UC1, cv::Scalar(1))); }, path,
      "CV_32FC1"));
  EXPECT_TRUE(dir.entries().empty());
}

// ---------------------------------------------------------------- Middlebury v2 --

TEST(MiddleburyV2, ReadsGroundTruth) {
  ScratchDir dir;
  const std::string path = dir.file("groundtruth.png");
  const cv::Mat gray = (cv::Mat_<std::uint8_t>(1, 4) << 0, 16, 255, 4);
  ASSERT_TRUE(cv::imwrite(path, gray));
  const cv::Mat disparity = flexsight::read_middlebury_v2_disparity(path, 16);
  ASSERT_EQ(disparity.type(), CV_32FC1);
  EXPECT_EQ(disparity.at<float>(0, 0), kInf);
  EXPECT_EQ(disparity.at<float>(0, 1), 1.0f);
  EXPECT_EQ(disparity.at<float>(0, 2), 15.9375f);
  EXPECT_EQ(disparity.at<float>(0, 3), 0.25f);

  const fs::path tsukuba = real_datasets_dir() / "middlebury-v2/tsukuba";
  ASSERT_TRUE(real_data_present(tsukuba / "groundtruth.png"));
  ASSERT_TRUE(real_data_present(tsukuba / "nonocc.png"));
  const cv::Mat gt =
      flexsight::read_middlebury_v2_disparity((tsukuba / "groundtruth.png").string(), 16);
  EXPECT_EQ(gt.size(), cv::Size(384, 288));
  EXPECT_TRUE(finite_values_within(gt, 16));
  const cv::Mat mask = flexsight::read_mask((tsukuba / "nonocc.png").string());
  EXPECT_EQ(mask.type(), CV_8UC1);
  EXPECT_EQ(mask.size(), gt.size());
}

TEST(MiddleburyV2, WriteImageRoundTrip) {
  // Ground truth written through write_image (8-bit gray) reads back as value / scale.
  ScratchDir dir;
  const std::string path = dir.file("disp.png");
  const cv::Mat gray = (cv::Mat_<std::uint8_t>(1, 3) << 0, 1, 200);
  flexsight::write_image(path, gray);
  const cv::Mat disparity = flexsight::read_middlebury_v2_disparity(path, 4);
  EXPECT_EQ(disparity.at<float>(0, 0), kInf);
  EXPECT_EQ(disparity.at<float>(0, 1), 0.25f);
  EXPECT_EQ(disparity.at<float>(0, 2), 50.0f);
}

TEST(MiddleburyV2, AcceptsThreeEqualChannelsRejectsColor) {
  ScratchDir dir;
  const std::string equal = dir.file("equal.png");
  ASSERT_TRUE(cv::imwrite(equal, cv::Mat(1, 2, CV_8UC3, cv::Scalar(8, 8, 8))));
  const cv::Mat disparity = flexsight::read_middlebury_v2_disparity(equal, 8);
  ASSERT_EQ(disparity.type(), CV_32FC1);
  EXPECT_EQ(disparity.at<float>(0, 1), 1.0f);

  const std::string color = dir.file("color.png");
  ASSERT_TRUE(cv::imwrite(color, cv::Mat(1, 2, CV_8UC3, cv::Scalar(8, 9, 8))));
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_middlebury_v2_disparity(color, 8); }, color,
                                 "channels differ"));
}

TEST(MiddleburyV2, RejectsSixteenBitAndBadScale) {
  ScratchDir dir;
  const std::string deep = dir.file("deep.png");
  ASSERT_TRUE(cv::imwrite(deep, cv::Mat(2, 2, CV_16UC1, cv::Scalar(300))));
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_middlebury_v2_disparity(deep, 4); }, deep,
                                 "unsupported bit depth 16U"));
  const std::string good = dir.file("good.png");
  ASSERT_TRUE(cv::imwrite(good, cv::Mat(2, 2, CV_8UC1, cv::Scalar(3))));
  for (double scale : {0.0, -4.0, std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_TRUE(throws_input_error([&] { flexsight::read_middlebury_v2_disparity(good, scale); },
                                   good, "scale must be a positive number"));
  }
  const std::string missing = dir.file("missing.png");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_middlebury_v2_disparity(missing, 4); },
                                 missing, "does not exist"));
}

TEST(MiddleburyV2, ReadsMasks) {
  ScratchDir dir;
  const std::string gray = dir.file("nonocc.png");
  const cv::Mat mask = (cv::Mat_<std::uint8_t>(1, 3) << 0, 128, 255);
  ASSERT_TRUE(cv::imwrite(gray, mask));
  const cv::Mat loaded = flexsight::read_mask(gray);
  ASSERT_EQ(loaded.type(), CV_8UC1);
  EXPECT_EQ(cv::countNonZero(loaded != mask), 0);

  const std::string three = dir.file("all.png");
  ASSERT_TRUE(cv::imwrite(three, cv::Mat(2, 2, CV_8UC3, cv::Scalar(255, 255, 255))));
  const cv::Mat from_three = flexsight::read_mask(three);
  ASSERT_EQ(from_three.type(), CV_8UC1);
  EXPECT_EQ(from_three.at<std::uint8_t>(1, 1), 255);
}

TEST(MiddleburyV2, MaskRejectsMissingAndSixteenBit) {
  ScratchDir dir;
  const std::string missing = dir.file("disc.png");
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::read_mask(missing); }, missing, "does not exist"));
  const std::string deep = dir.file("deep.png");
  ASSERT_TRUE(cv::imwrite(deep, cv::Mat(2, 2, CV_16UC1, cv::Scalar(255))));
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::read_mask(deep); }, deep, "unsupported bit depth 16U"));
}

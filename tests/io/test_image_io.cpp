// Tests of the image I/O (host/io/image_io.h): round trips through every format we
// write, and a clear InputError naming the file for every kind of malformed input.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "host/io/image_io.h"
#include "tests/io/io_test_support.h"

using namespace flexsight::io_test_support;

// ------------------------------------------------------------ load_rgb8 / write_image --

TEST(ImageIo, RoundTrip8BitGray) {
  ScratchDir dir;
  const std::string path = dir.file("gray8.png");
  const cv::Mat gray = (cv::Mat_<std::uint8_t>(2, 3) << 0, 1, 127, 128, 254, 255);
  flexsight::write_image(path, gray);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"gray8.png"});

  const cv::Mat rgb = flexsight::load_rgb8(path);
  ASSERT_EQ(rgb.type(), CV_8UC3);
  ASSERT_EQ(rgb.size(), gray.size());
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) {
      const std::uint8_t g = gray.at<std::uint8_t>(y, x);
      EXPECT_EQ(rgb.at<cv::Vec3b>(y, x), cv::Vec3b(g, g, g)) << y << "," << x;
    }
  }
}

TEST(ImageIo, RoundTrip8BitColorKeepsRgbOrder) {
  ScratchDir dir;
  const std::string path = dir.file("color8.png");
  cv::Mat rgb(1, 2, CV_8UC3);
  rgb.at<cv::Vec3b>(0, 0) = cv::Vec3b(200, 100, 10);  // R, G, B
  rgb.at<cv::Vec3b>(0, 1) = cv::Vec3b(1, 2, 3);
  flexsight::write_image(path, rgb);

  // On disk the PNG must hold the same colours: OpenCV reads it back as BGR.
  const cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(raw.type(), CV_8UC3);
  EXPECT_EQ(raw.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 100, 200));

  const cv::Mat loaded = flexsight::load_rgb8(path);
  ASSERT_EQ(loaded.type(), CV_8UC3);
  EXPECT_EQ(loaded.at<cv::Vec3b>(0, 0), cv::Vec3b(200, 100, 10));
  EXPECT_EQ(loaded.at<cv::Vec3b>(0, 1), cv::Vec3b(1, 2, 3));
}

TEST(ImageIo, RoundTrip16BitGrayRoundsTo8Bit) {
  ScratchDir dir;
  const std::string path = dir.file("gray16.png");
  const std::vector<std::uint16_t> values = {0, 128, 129, 385, 386, 32896, 65406, 65407, 65535};
  // (v + 128) / 257 in integers.
  const std::vector<std::uint8_t> expected = {0, 0, 1, 1, 2, 128, 254, 255, 255};
  cv::Mat gray(1, static_cast<int>(values.size()), CV_16UC1);
  for (std::size_t i = 0; i < values.size(); ++i) gray.at<std::uint16_t>(0, int(i)) = values[i];
  flexsight::write_image(path, gray);

  const cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(raw.type(), CV_16UC1);
  EXPECT_EQ(cv::countNonZero(raw != gray), 0);

  const cv::Mat rgb = flexsight::load_rgb8(path);
  ASSERT_EQ(rgb.type(), CV_8UC3);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::uint8_t e = expected[i];
    EXPECT_EQ(rgb.at<cv::Vec3b>(0, int(i)), cv::Vec3b(e, e, e)) << "16-bit value " << values[i];
  }
}

TEST(ImageIo, RoundTrip16BitColorKeepsRgbOrder) {
  ScratchDir dir;
  const std::string path = dir.file("color16.png");
  cv::Mat rgb(1, 2, CV_16UC3);
  rgb.at<cv::Vec3w>(0, 0) = cv::Vec3w(65535, 32896, 0);  // R, G, B
  rgb.at<cv::Vec3w>(0, 1) = cv::Vec3w(257, 386, 129);
  flexsight::write_image(path, rgb);

  const cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_EQ(raw.type(), CV_16UC3);
  EXPECT_EQ(raw.at<cv::Vec3w>(0, 0), cv::Vec3w(0, 32896, 65535));  // BGR on disk

  const cv::Mat loaded = flexsight::load_rgb8(path);
  ASSERT_EQ(loaded.type(), CV_8UC3);
  EXPECT_EQ(loaded.at<cv::Vec3b>(0, 0), cv::Vec3b(255, 128, 0));
  EXPECT_EQ(loaded.at<cv::Vec3b>(0, 1), cv::Vec3b(1, 2, 1));
}

TEST(ImageIo, LoadDropsAlpha) {
  ScratchDir dir;
  const std::string path = dir.file("bgra.png");
  cv::Mat bgra(1, 1, CV_8UC4, cv::Scalar(30, 20, 10, 77));
  ASSERT_TRUE(cv::imwrite(path, bgra));
  const cv::Mat rgb = flexsight::load_rgb8(path);
  ASSERT_EQ(rgb.type(), CV_8UC3);
  EXPECT_EQ(rgb.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 30));
}

TEST(ImageIo, WriteImageChoosesEncoderFromFinalExtension) {
  ScratchDir dir;
  const std::string path = dir.file("image.ppm");
  flexsight::write_image(path, cv::Mat(2, 2, CV_8UC3, cv::Scalar(1, 2, 3)));
  EXPECT_EQ(read_bytes(path).substr(0, 2), "P6");
  EXPECT_EQ(flexsight::load_rgb8(path).at<cv::Vec3b>(1, 1), cv::Vec3b(1, 2, 3));
}

TEST(ImageIo, WriteImageRejectsUnknownExtensionAndLeavesNothing) {
  ScratchDir dir;
  const std::string path = dir.file("image.notaformat");
  EXPECT_TRUE(throws_input_error(
      [&] { flexsight::write_image(path, cv::Mat(2, 2, CV_8UC1, cv::Scalar(5))); }, path,
      "cannot be"));
  EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageIo, WriteImageRejectsFloatAndEmptyImages) {
  ScratchDir dir;
  const std::string path = dir.file("float.png");
  EXPECT_TRUE(throws_input_error(
      [&] { flexsight::write_image(path, cv::Mat(2, 2, CV_32FC1, cv::Scalar(0.5))); }, path,
      "unsupported bit depth 32F"));
  EXPECT_TRUE(throws_input_error([&] { flexsight::write_image(path, cv::Mat()); }, path, "empty"));
  EXPECT_TRUE(dir.entries().empty());
}

TEST(ImageIo, LoadRejectsMissingEmptyAndDirectory) {
  ScratchDir dir;
  const std::string missing = dir.file("missing.png");
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::load_rgb8(missing); }, missing, "does not exist"));
  const std::string empty = dir.file("empty.png");
  write_bytes(empty, "");
  EXPECT_TRUE(throws_input_error([&] { flexsight::load_rgb8(empty); }, empty, "is empty"));
  const std::string folder = dir.file("folder.png");
  fs::create_directories(folder);
  EXPECT_TRUE(throws_input_error([&] { flexsight::load_rgb8(folder); }, folder, "directory"));
}

TEST(ImageIo, LoadRejectsTextFileNamedPng) {
  ScratchDir dir;
  const std::string path = dir.file("notes.png");
  write_bytes(path, "this is not an image\n");
  EXPECT_TRUE(throws_input_error([&] { flexsight::load_rgb8(path); }, path,
                                 "cannot be decoded as an image"));
}

TEST(ImageIo, LoadRejectsFloatTiff) {
  ScratchDir dir;
  const std::string path = dir.file("float.tiff");
  ASSERT_TRUE(cv::imwrite(path, cv::Mat(3, 3, CV_32FC1, cv::Scalar(0.25))));
  EXPECT_TRUE(throws_input_error([&] { flexsight::load_rgb8(path); }, path,
                                 "unsupported bit depth 32F (expected 8- or 16-bit)"));
}

TEST(ImageIo, StereoPairLoadsBothViews) {
  ScratchDir dir;
  const std::string left = dir.file("left.png");
  const std::string right = dir.file("right.png");
  flexsight::write_image(left, cv::Mat(3, 4, CV_8UC3, cv::Scalar(1, 2, 3)));
  flexsight::write_image(right, cv::Mat(3, 4, CV_8UC1, cv::Scalar(9)));
  const flexsight::StereoPair pair = flexsight::load_stereo_pair(left, right);
  EXPECT_EQ(pair.left.at<cv::Vec3b>(2, 3), cv::Vec3b(1, 2, 3));
  EXPECT_EQ(pair.right.at<cv::Vec3b>(2, 3), cv::Vec3b(9, 9, 9));
}

TEST(ImageIo, StereoPairRejectsMismatchedSizes) {
  ScratchDir dir;
  const std::string left = dir.file("left.png");
  const std::string right = dir.file("right.png");
  flexsight::write_image(left, cv::Mat(3, 4, CV_8UC3, cv::Scalar(0)));
  flexsight::write_image(right, cv::Mat(3, 5, CV_8UC3, cv::Scalar(0)));
  const auto load = [&] { flexsight::load_stereo_pair(left, right); };
  EXPECT_TRUE(throws_input_error(load, right, "is 5x3"));
  EXPECT_TRUE(throws_input_error(load, right, "4x3"));
  EXPECT_TRUE(throws_input_error(load, left, "left image"));
}

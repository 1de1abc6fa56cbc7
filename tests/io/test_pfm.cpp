// Tests of the PFM reader and writer (host/io/pfm.h): round trips, exact decoding of
// hand-written files in both byte orders, and a clear InputError naming the file for
// every kind of malformed input.
//
// The tests that check a format on synthetic files also read the real files of that
// format, from the datasets folder of tests/common/real_datasets.h; a missing real file
// fails them.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/io/pfm.h"
#include "tests/io/io_test_support.h"

using namespace flexsight::io_test_support;

// -------------------------------------------------------------------------- PFM --

TEST(Pfm, RoundTripLittleEndian) {
  ScratchDir dir;
  const std::string path = dir.file("disp.pfm");
  const cv::Mat disparity = (cv::Mat_<float>(2, 3) << 1.5f, kInf, -0.25f, 1e-30f, 3.4e38f, 0.0f);
  flexsight::write_pfm(path, disparity);

  // Little-endian header with scale -1, bottom row first.
  const std::string bytes = read_bytes(path);
  const std::string header = "Pf\n3 2\n-1\n";
  ASSERT_EQ(bytes.size(), header.size() + 6 * 4);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  EXPECT_EQ(bytes.substr(header.size(), 4), float_bytes(1e-30f, true));

  const cv::Mat loaded = flexsight::read_pfm(path);
  ASSERT_EQ(loaded.type(), CV_32FC1);
  ASSERT_EQ(loaded.size(), disparity.size());
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) {
      EXPECT_EQ(loaded.at<float>(y, x), disparity.at<float>(y, x)) << y << "," << x;
    }
  }
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"disp.pfm"});
}

TEST(Pfm, RoundTripThreeChannels) {
  ScratchDir dir;
  const std::string path = dir.file("color.pfm");
  cv::Mat image(2, 2, CV_32FC3);
  image.at<cv::Vec3f>(0, 0) = cv::Vec3f(kInf, 1, 2);
  image.at<cv::Vec3f>(0, 1) = cv::Vec3f(3, -kInf, 5);
  image.at<cv::Vec3f>(1, 0) = cv::Vec3f(0.125f, 7, 8);
  image.at<cv::Vec3f>(1, 1) = cv::Vec3f(9, 10, kInf);
  flexsight::write_pfm(path, image);
  EXPECT_EQ(read_bytes(path).substr(0, 3), "PF\n");

  const cv::Mat loaded = flexsight::read_pfm(path);
  ASSERT_EQ(loaded.type(), CV_32FC3);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 2; ++x) {
      EXPECT_EQ(loaded.at<cv::Vec3f>(y, x), image.at<cv::Vec3f>(y, x)) << y << "," << x;
    }
  }
}

TEST(Pfm, ReadsBigEndianFile) {
  ScratchDir dir;
  const std::string path = dir.file("big.pfm");
  // Positive scale = big-endian. Rows are stored bottom-up: the file's first row is
  // the image's last.
  std::string bytes = "Pf\n2 2\n1.0\n";
  for (float v : {3.5f, kInf, 1.25f, -2.0f}) bytes += float_bytes(v, false);
  write_bytes(path, bytes);

  const cv::Mat loaded = flexsight::read_pfm(path);
  ASSERT_EQ(loaded.type(), CV_32FC1);
  ASSERT_EQ(loaded.size(), cv::Size(2, 2));
  EXPECT_EQ(loaded.at<float>(0, 0), 1.25f);
  EXPECT_EQ(loaded.at<float>(0, 1), -2.0f);
  EXPECT_EQ(loaded.at<float>(1, 0), 3.5f);
  EXPECT_EQ(loaded.at<float>(1, 1), kInf);
}

TEST(Pfm, ReadsBigEndianThreeChannelFile) {
  ScratchDir dir;
  const std::string path = dir.file("big3.pfm");
  std::string bytes = "PF\n1 1\n2.5\n";
  for (float v : {0.5f, 1e6f, -kInf}) bytes += float_bytes(v, false);
  write_bytes(path, bytes);
  const cv::Mat loaded = flexsight::read_pfm(path);
  ASSERT_EQ(loaded.type(), CV_32FC3);
  EXPECT_EQ(loaded.at<cv::Vec3f>(0, 0), cv::Vec3f(0.5f, 1e6f, -kInf));
}

TEST(Pfm, HeaderFieldsMayStandBetweenSpacesAndTabs) {
  ScratchDir dir;
  const std::string path = dir.file("spaced.pfm");
  // Exactly one whitespace byte after the scale: the data's first byte is 0x20 (a
  // space) here, which a parser that skips all whitespace would eat.
  const float space_first = [] {
    const std::uint32_t bits = 0x3F800020u;  // little-endian bytes 20 00 80 3F
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }();
  write_bytes(path, "Pf\n  2\t  1 \n-1.0\n" + floats_le({space_first, 7.0f}));
  const cv::Mat loaded = flexsight::read_pfm(path);
  ASSERT_EQ(loaded.size(), cv::Size(2, 1));
  EXPECT_EQ(loaded.at<float>(0, 0), space_first);
  EXPECT_EQ(loaded.at<float>(0, 1), 7.0f);
}

TEST(Pfm, ReadsHeaderLinesEndedByCarriageReturnAndNewline) {
  ScratchDir dir;
  const std::string path = dir.file("windows.pfm");
  // 0x0A as the first data byte: the data starts right after the scale line's "\r\n".
  const float newline_first = [] {
    const std::uint32_t bits = 0x3F80000Au;
    float v;
    std::memcpy(&v, &bits, sizeof v);
    return v;
  }();
  write_bytes(path, "Pf\r\n1 1\r\n-1\r\n" + floats_le({newline_first}));
  EXPECT_EQ(flexsight::read_pfm(path).at<float>(0, 0), newline_first);
}

// The header is exactly three lines: tokens on the wrong line are not taken for others,
// and bytes after the data are refused, not ignored.
TEST(Pfm, RejectsHeadersThatAreNotThreeExactLines) {
  ScratchDir dir;
  struct Case {
    const char* name;
    std::string bytes;
    const char* expected;
  };
  const std::string data_64x48 = std::string(64 * 48 * 4, '\0');
  const std::vector<Case> cases = {
      {"three_on_size_line.pfm", "Pf\n64 48 7\n-1\n" + data_64x48, "3 fields on its size line"},
      {"junk_after_scale.pfm", "Pf\n64 48\n-1 junk\n" + data_64x48, "2 fields on its scale line"},
      {"one_on_size_line.pfm", "Pf\n64\n48\n-1\n" + data_64x48, "1 fields on its size line"},
      {"comment.pfm", "Pf\n# by hand\n64 48\n-1\n" + data_64x48, "fields on its size line"},
      {"blank_line.pfm", "Pf\n64 48\n\n-1\n" + data_64x48, "0 fields on its scale line"},
      {"magic_with_more.pfm", "Pf 64 48\n-1\n" + data_64x48, "is not a PFM file"},
      {"trailing_bytes.pfm", "Pf\n64 48\n-1\n" + data_64x48 + "xyz", "has 3 bytes after the 64x48x1 image"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.file(c.name);
    write_bytes(path, c.bytes);
    EXPECT_TRUE(throws_input_error([&] { flexsight::read_pfm(path); }, path, c.expected)) << c.name;
  }
}

TEST(Pfm, ReadsMiddleburyGroundTruth) {
  // Synthetic file laid out like Middlebury's disp0GT.pfm (scale -1/255, inf = unknown).
  ScratchDir dir;
  const std::string path = dir.file("disp0GT.pfm");
  const int width = 741, height = 497;
  std::string bytes =
      "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-0.003922\n";
  for (int i = 0; i < width * height; ++i) {
    bytes += float_bytes(i % 7 == 0 ? kInf : 1.0f + float(i % 60), true);
  }
  write_bytes(path, bytes);
  const cv::Mat synthetic = flexsight::read_pfm(path);
  EXPECT_EQ(synthetic.size(), cv::Size(width, height));
  EXPECT_EQ(count_inf(synthetic), (width * height + 6) / 7);
  EXPECT_TRUE(finite_values_within(synthetic, 70));

  const fs::path real = real_datasets_dir() / "MiddEval3-trainingQ/Motorcycle/disp0GT.pfm";
  ASSERT_TRUE(real_data_present(real));
  const cv::Mat gt = flexsight::read_pfm(real.string());
  ASSERT_EQ(gt.type(), CV_32FC1);
  EXPECT_EQ(gt.size(), cv::Size(741, 497));
  EXPECT_GT(count_inf(gt), 0);
  EXPECT_LT(count_inf(gt), gt.rows * gt.cols / 2);
  EXPECT_TRUE(finite_values_within(gt, 70));  // Motorcycle: ndisp=70
}

TEST(Pfm, RejectsMissingAndEmptyFiles) {
  ScratchDir dir;
  const std::string missing = dir.file("missing.pfm");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_pfm(missing); }, missing, "does not exist"));
  const std::string empty = dir.file("empty.pfm");
  write_bytes(empty, "");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_pfm(empty); }, empty, "is empty"));
}

TEST(Pfm, RejectsTruncatedData) {
  ScratchDir dir;
  const std::string path = dir.file("truncated.pfm");
  write_bytes(path, "Pf\n10 10\n-1\n" + std::string(120, '\0'));
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_pfm(path); }, path,
                                 "header says 10x10x1 (400 bytes) but only 120 bytes"));
}

TEST(Pfm, RejectsBadMagic) {
  ScratchDir dir;
  const std::string path = dir.file("color.pfm");
  write_bytes(path, "P6\n2 2\n255\n" + std::string(12, '\x7f'));
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_pfm(path); }, path,
                                 "is not a PFM file (first line 'P6'"));
}

TEST(Pfm, RejectsNonPositiveAndMalformedDimensions) {
  ScratchDir dir;
  const std::string negative = dir.file("negative.pfm");
  write_bytes(negative, "Pf\n-4 4\n-1\n" + std::string(64, '\0'));
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_pfm(negative); }, negative,
                                 "non-positive dimensions -4x4"));
  const std::string zero = dir.file("zero.pfm");
  write_bytes(zero, "Pf\n4 0\n-1\n");
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::read_pfm(zero); }, zero, "non-positive dimensions 4x0"));
  const std::string text = dir.file("text.pfm");
  write_bytes(text, "Pf\nfour 4\n-1\n" + std::string(64, '\0'));
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::read_pfm(text); }, text, "malformed width 'four'"));
}

TEST(Pfm, RejectsZeroOrMalformedScale) {
  ScratchDir dir;
  const std::string zero = dir.file("zero_scale.pfm");
  write_bytes(zero, "Pf\n1 1\n0.0\n" + floats_le({1.0f}));
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_pfm(zero); }, zero, "zero scale"));
  const std::string text = dir.file("text_scale.pfm");
  write_bytes(text, "Pf\n1 1\nbig\n" + floats_le({1.0f}));
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_pfm(text); }, text, "malformed scale"));
}

TEST(Pfm, RejectsIncompleteHeader) {
  ScratchDir dir;
  const std::string short_header = dir.file("short.pfm");
  write_bytes(short_header, "Pf\n2");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_pfm(short_header); }, short_header,
                                 "header ends before the end of its size line"));
  const std::string no_data = dir.file("nodata.pfm");
  write_bytes(no_data, "Pf\n2 2\n-1");
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::read_pfm(no_data); }, no_data, "header ends before the end of its scale line"));
}

TEST(Pfm, WriteRejectsUnsupportedTypes) {
  ScratchDir dir;
  const std::string path = dir.file("bytes.pfm");
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::write_pfm(path, cv::Mat(2, 2, CV_8UC1, cv::Scalar(1))); },
                         path, "CV_32FC1 or CV_32FC3"));
  EXPECT_TRUE(dir.entries().empty());
}

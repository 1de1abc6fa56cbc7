// Tests of image_size_from_header (host/io/image_header.h): the size the header gives
// is the size the decoder gives, for every format we read, and a header cut short or
// damaged is an InputError naming the file.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "host/io/image_header.h"
#include "tests/io/io_test_support.h"

using namespace flexsight::io_test_support;
using flexsight::image_size_from_header;

namespace {

cv::Mat pattern(int width, int height, int type) {
  cv::Mat image(height, width, type);
  cv::randu(image, 0, 255);
  return image;
}

}  // namespace

TEST(ImageHeader, SizeOfEveryFormatMatchesTheDecoder) {
  ScratchDir dir;
  const std::vector<std::pair<std::string, int>> files = {
      {"gray.png", CV_8UC1}, {"depth.png", CV_16UC1}, {"color.jpg", CV_8UC3}, {"gray.jpg", CV_8UC1},
      {"color.tif", CV_8UC3}, {"color.bmp", CV_8UC3}};
  for (const auto& [name, type] : files) {
    const std::string path = dir.file(name);
    ASSERT_TRUE(cv::imwrite(path, pattern(37, 21, type))) << name;
    EXPECT_EQ(image_size_from_header(path), cv::Size(37, 21)) << name;
    EXPECT_EQ(image_size_from_header(path), cv::imread(path, cv::IMREAD_UNCHANGED).size()) << name;
  }
}

TEST(ImageHeader, ProgressiveJpegWithMetadataBeforeTheFrame) {
  ScratchDir dir;
  const std::string path = dir.file("progressive.jpg");
  ASSERT_TRUE(cv::imwrite(path, pattern(640, 7, CV_8UC3), {cv::IMWRITE_JPEG_PROGRESSIVE, 1}));
  EXPECT_EQ(image_size_from_header(path), cv::Size(640, 7));
}

TEST(ImageHeader, DamagedHeadersNameTheFile) {
  ScratchDir dir;
  const std::string png = dir.file("a.png");
  ASSERT_TRUE(cv::imwrite(png, pattern(8, 4, CV_8UC1)));
  const std::string bytes = read_bytes(png);

  const std::string cut = dir.file("cut.png");
  write_bytes(cut, bytes.substr(0, 20));
  EXPECT_TRUE(throws_input_error([&] { image_size_from_header(cut); }, cut, "IHDR"));

  std::string zero = bytes;
  zero.replace(16, 4, std::string(4, '\0'));  // IHDR width 0
  const std::string zero_path = dir.file("zero.png");
  write_bytes(zero_path, zero);
  EXPECT_TRUE(throws_input_error([&] { image_size_from_header(zero_path); }, zero_path, "0x4"));

  const std::string junk = dir.file("junk.jpg");
  write_bytes(junk, "\xff\xd8\xff\xe0 not a jpeg at all");
  EXPECT_TRUE(throws_input_error([&] { image_size_from_header(junk); }, junk, "decoded"));

  const std::string missing = dir.file("missing.png");
  EXPECT_TRUE(throws_input_error([&] { image_size_from_header(missing); }, missing, "does not exist"));
}

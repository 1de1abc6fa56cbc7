// Tests of the stereo I/O layer (host/io): round trips through every format we write,
// exact decoding of hand-written files, and a clear InputError naming the file for
// every kind of malformed input.
//
// The tests that check a format on synthetic files also read the real files of that
// format, from the datasets folder of tests/common/real_datasets.h; a missing real file
// fails them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/io/atomic_file.h"
#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/kitti_disparity.h"
#include "host/io/middlebury_v2.h"
#include "host/io/pfm.h"
#include "tests/common/real_datasets.h"

namespace {

namespace fs = std::filesystem;
using flexsight::InputError;

const float kInf = std::numeric_limits<float>::infinity();

// A fresh, empty folder per test, removed afterwards. The pid keeps concurrent runs of
// the test binary (e.g. ctest -j) apart.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    const std::string name = std::string("flexsight_io_") + info->test_suite_name() + "_" +
                             info->name() + "_" + std::to_string(::getpid());
    path_ = fs::path(testing::TempDir()) / name;
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }

  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream contents;
  contents << in.rdbuf();
  return contents.str();
}

// Checks that `action` throws InputError whose message names `path` and contains
// `fragment`. Used as EXPECT_TRUE(throws_input_error(...)) so failures point at the call.
testing::AssertionResult throws_input_error(const std::function<void()>& action,
                                            const std::string& path, const std::string& fragment) {
  try {
    action();
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (message.find(path) == std::string::npos) {
      return testing::AssertionFailure() << "message does not name " << path << ": " << message;
    }
    if (message.find(fragment) == std::string::npos) {
      return testing::AssertionFailure() << "message lacks '" << fragment << "': " << message;
    }
    return testing::AssertionSuccess();
  } catch (const std::exception& e) {
    return testing::AssertionFailure() << "threw another exception type: " << e.what();
  }
  return testing::AssertionFailure() << "no exception for " << path;
}

// Float bytes in a chosen order, independent of the host's order.
std::string float_bytes(float value, bool little_endian) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  std::string out(4, '\0');
  for (int i = 0; i < 4; ++i) {
    const int shift = little_endian ? 8 * i : 8 * (3 - i);
    out[i] = static_cast<char>((bits >> shift) & 0xFFu);
  }
  return out;
}

std::string floats_le(const std::vector<float>& values) {
  std::string out;
  for (float v : values) out += float_bytes(v, true);
  return out;
}

using flexsight::testing_support::real_data_present;
using flexsight::testing_support::real_datasets_dir;

int count_inf(const cv::Mat& disparity) {
  int count = 0;
  for (int y = 0; y < disparity.rows; ++y) {
    for (int x = 0; x < disparity.cols; ++x) count += std::isinf(disparity.at<float>(y, x));
  }
  return count;
}

// Finite values of a disparity map all lie in (0, max_disparity].
bool finite_values_within(const cv::Mat& disparity, float max_disparity) {
  for (int y = 0; y < disparity.rows; ++y) {
    for (int x = 0; x < disparity.cols; ++x) {
      const float d = disparity.at<float>(y, x);
      if (std::isfinite(d) && !(d > 0 && d <= max_disparity)) return false;
      if (std::isnan(d)) return false;
    }
  }
  return true;
}

const char kMotorcycleCalib[] =
    "cam0=[999.421 0 294.182; 0 999.421 252.932; 0 0 1]\n"
    "cam1=[999.421 0 326.96; 0 999.421 252.932; 0 0 1]\n"
    "doffs=32.778\n"
    "baseline=193.001\n"
    "width=741\n"
    "height=497\n"
    "ndisp=70\n"
    "isint=0\n"
    "vmin=7\n"
    "vmax=65\n"
    "dyavg=0.23\n"
    "dymax=0.379\n";

// kMotorcycleCalib with the line starting with `key=` replaced by `line` ("" drops it).
std::string motorcycle_calib_with(const std::string& key, const std::string& line) {
  std::istringstream in(kMotorcycleCalib);
  std::string out;
  for (std::string current; std::getline(in, current);) {
    if (current.rfind(key + "=", 0) == 0) {
      if (!line.empty()) out += line + "\n";
    } else {
      out += current + "\n";
    }
  }
  return out;
}

const char kKitti2012Calib[] =
    "P0: 7.188560e+02 0.000000e+00 6.071928e+02 0.000000e+00 0.000000e+00 7.188560e+02 "
    "1.852157e+02 0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00\n"
    "P1: 7.188560e+02 0.000000e+00 6.071928e+02 -3.861448e+02 0.000000e+00 7.188560e+02 "
    "1.852157e+02 0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00\n"
    "P2: 7.188560e+02 0.000000e+00 6.071928e+02 4.538225e+01 0.000000e+00 7.188560e+02 "
    "1.852157e+02 -1.130887e-01 0.000000e+00 0.000000e+00 1.000000e+00 3.779761e-03\n";

}  // namespace

// ---------------------------------------------------------------- write_atomically --

TEST(AtomicFile, RenamesTemporaryIntoPlace) {
  ScratchDir dir;
  const std::string path = dir.file("result.png");
  std::string seen_tmp;
  flexsight::write_atomically(path, [&](const std::string& tmp) {
    seen_tmp = tmp;
    write_bytes(tmp, "payload");
  });
  EXPECT_EQ(read_bytes(path), "payload");
  EXPECT_NE(seen_tmp, path);
  // Same folder (the rename never crosses file systems), same extension (imwrite).
  EXPECT_EQ(fs::path(seen_tmp).parent_path(), dir.path());
  EXPECT_EQ(fs::path(seen_tmp).extension(), ".png");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"result.png"});
}

TEST(AtomicFile, TemporaryNamesAreUnique) {
  ScratchDir dir;
  std::vector<std::string> tmps;
  for (int i = 0; i < 3; ++i) {
    flexsight::write_atomically(dir.file("a.pfm"), [&](const std::string& tmp) {
      tmps.push_back(tmp);
      write_bytes(tmp, "x");
    });
  }
  std::sort(tmps.begin(), tmps.end());
  EXPECT_EQ(std::unique(tmps.begin(), tmps.end()), tmps.end());
}

TEST(AtomicFile, FailureRemovesTemporaryKeepsOldFileAndRethrows) {
  ScratchDir dir;
  const std::string path = dir.file("out.txt");
  write_bytes(path, "old");
  EXPECT_THROW(flexsight::write_atomically(path,
                                           [&](const std::string& tmp) {
                                             write_bytes(tmp, "partial");
                                             throw std::runtime_error("encoder failed");
                                           }),
               std::runtime_error);
  EXPECT_EQ(read_bytes(path), "old");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.txt"});
}

TEST(AtomicFile, FailedRenameThrowsInputErrorNamingTarget) {
  ScratchDir dir;
  // A non-empty directory cannot be replaced by a file.
  const std::string path = dir.file("occupied");
  fs::create_directories(fs::path(path) / "child");
  EXPECT_TRUE(throws_input_error(
      [&] {
        flexsight::write_atomically(path, [](const std::string& tmp) { write_bytes(tmp, "x"); });
      },
      path, "cannot be written"));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"occupied"});
}

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

TEST(Pfm, HeaderToleratesCommentsAndExtraWhitespace) {
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
  write_bytes(path, "Pf\n# written by hand\n  2\t  1 \n\n-1.0\n" + floats_le({space_first, 7.0f}));
  const cv::Mat loaded = flexsight::read_pfm(path);
  ASSERT_EQ(loaded.size(), cv::Size(2, 1));
  EXPECT_EQ(loaded.at<float>(0, 0), space_first);
  EXPECT_EQ(loaded.at<float>(0, 1), 7.0f);
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
                                 "is not a PFM file (magic 'P6'"));
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
                                 "header ends before the height"));
  const std::string no_data = dir.file("nodata.pfm");
  write_bytes(no_data, "Pf\n2 2\n-1");
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::read_pfm(no_data); }, no_data, "header ends without"));
}

TEST(Pfm, WriteRejectsUnsupportedTypes) {
  ScratchDir dir;
  const std::string path = dir.file("bytes.pfm");
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::write_pfm(path, cv::Mat(2, 2, CV_8UC1, cv::Scalar(1))); },
                         path, "CV_32FC1 or CV_32FC3"));
  EXPECT_TRUE(dir.entries().empty());
}

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

// ------------------------------------------------------------------ calibration --

TEST(Calibration, ReadsMiddleburyCalib) {
  ScratchDir dir;
  const std::string path = dir.file("calib.txt");
  write_bytes(path, kMotorcycleCalib);
  const flexsight::MiddleburyCalib calib = flexsight::read_middlebury_calib(path);
  const std::array<double, 9> cam0 = {999.421, 0, 294.182, 0, 999.421, 252.932, 0, 0, 1};
  const std::array<double, 9> cam1 = {999.421, 0, 326.96, 0, 999.421, 252.932, 0, 0, 1};
  EXPECT_EQ(calib.cam0, cam0);
  EXPECT_EQ(calib.cam1, cam1);
  EXPECT_EQ(calib.doffs, 32.778);
  EXPECT_EQ(calib.baseline_mm, 193.001);
  EXPECT_EQ(calib.width, 741);
  EXPECT_EQ(calib.height, 497);
  EXPECT_EQ(calib.ndisp, 70);
  EXPECT_EQ(calib.vmin, 7);
  EXPECT_EQ(calib.vmax, 65);

  // Every scene's calib.txt parses and agrees with the size of its left image.
  const fs::path middeval3 = real_datasets_dir() / "MiddEval3-trainingQ";
  ASSERT_TRUE(real_data_present(middeval3));
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(middeval3)) {
    const fs::path calib_path = entry.path() / "calib.txt";
    if (!fs::exists(calib_path)) continue;
    SCOPED_TRACE(calib_path.string());
    ++scenes;
    const flexsight::MiddleburyCalib real = flexsight::read_middlebury_calib(calib_path.string());
    const cv::Mat left = flexsight::load_rgb8((entry.path() / "im0.png").string());
    EXPECT_EQ(cv::Size(real.width, real.height), left.size());
    EXPECT_GT(real.ndisp, 0);
    EXPECT_LE(0, real.vmin);
    EXPECT_LT(real.vmin, real.vmax);
    EXPECT_LE(real.vmax, real.ndisp);
    EXPECT_EQ(real.cam0[0], real.cam1[0]);  // rectified: same focal length
  }
  EXPECT_EQ(scenes, 15) << "calib.txt files under " << middeval3;
}

TEST(Calibration, MiddleburyToleratesCrlfSpacesAndMissingOptionalKeys) {
  ScratchDir dir;
  const std::string path = dir.file("calib.txt");
  write_bytes(path,
              "cam0 = [ 10 0 5 ; 0 10 4 ; 0 0 1 ]\r\n"
              "cam1=[10 0 6; 0 10 4; 0 0 1]\r\n"
              "\r\n"
              "doffs=1\r\nbaseline=2.5\r\nwidth=8\r\nheight=6\r\nndisp=4\r\n");
  const flexsight::MiddleburyCalib calib = flexsight::read_middlebury_calib(path);
  EXPECT_EQ(calib.cam0[2], 5.0);
  EXPECT_EQ(calib.cam1[2], 6.0);
  EXPECT_EQ(calib.baseline_mm, 2.5);
  EXPECT_EQ(calib.ndisp, 4);
  EXPECT_EQ(calib.vmin, -1);
  EXPECT_EQ(calib.vmax, -1);
}

TEST(Calibration, MiddleburyRejectsMissingKeys) {
  ScratchDir dir;
  for (const char* key : {"ndisp", "cam0", "cam1", "doffs", "baseline", "width", "height"}) {
    const std::string path = dir.file(std::string("no_") + key + ".txt");
    write_bytes(path, motorcycle_calib_with(key, ""));
    EXPECT_TRUE(throws_input_error([&] { flexsight::read_middlebury_calib(path); }, path,
                                   std::string("missing key '") + key + "'"));
  }
}

TEST(Calibration, MiddleburyRejectsMalformedValues) {
  ScratchDir dir;
  struct Case {
    const char* key;
    const char* line;
    const char* problem;
  };
  const Case cases[] = {
      {"cam0", "cam0=[999.421 0 294.182; 0 999.421]", "key 'cam0' is not a 3x3 matrix"},
      {"cam0", "cam0=999.421 0 294.182; 0 999.421 252.932; 0 0 1", "key 'cam0' is not a 3x3"},
      {"cam1", "cam1=[999.421 0 x; 0 999.421 252.932; 0 0 1]", "key 'cam1' is not a 3x3"},
      {"cam1", "cam1=[1 0 2; 0 1 3; 0 0 1; 0 0 0]", "key 'cam1' is not a 3x3"},
      {"cam1", "cam1=[-5 0 326.96; 0 999.421 252.932; 0 0 1]", "key 'cam1' has a focal length"},
      {"width", "width=abc", "key 'width' is not an integer: 'abc'"},
      {"height", "height=497.5", "key 'height' is not an integer"},
      {"doffs", "doffs=", "key 'doffs' is not a number"},
      {"ndisp", "ndisp=0", "key 'ndisp' must be positive, got 0"},
      {"width", "width=-741", "key 'width' must be positive"},
      {"baseline", "baseline=-1", "key 'baseline' must be positive"},
      {"vmin", "vmin=seven", "key 'vmin' is not an integer"},
      {"isint", "this line has no equals sign", "line 8 is not 'key=value'"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.file(std::string("bad_") + c.key + ".txt");
    write_bytes(path, motorcycle_calib_with(c.key, c.line));
    EXPECT_TRUE(
        throws_input_error([&] { flexsight::read_middlebury_calib(path); }, path, c.problem))
        << c.line;
  }
  const std::string twice = dir.file("twice.txt");
  write_bytes(twice, std::string(kMotorcycleCalib) + "ndisp=80\n");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_middlebury_calib(twice); }, twice,
                                 "key 'ndisp' appears more than once"));
}

TEST(Calibration, MiddleburyRejectsMissingAndEmptyFiles) {
  ScratchDir dir;
  const std::string missing = dir.file("calib.txt");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_middlebury_calib(missing); }, missing,
                                 "does not exist"));
  const std::string empty = dir.file("empty.txt");
  write_bytes(empty, "");
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::read_middlebury_calib(empty); }, empty, "is empty"));
}

TEST(Calibration, ReadsKitti2012Calib) {
  ScratchDir dir;
  const std::string path = dir.file("000070.txt");
  write_bytes(path, kKitti2012Calib);
  const flexsight::KittiCalib calib = flexsight::read_kitti_calib(path);
  EXPECT_EQ(calib.P0[2], 607.1928);
  EXPECT_EQ(calib.P1[3], -386.1448);
  EXPECT_EQ(calib.focal_px(), 718.856);
  EXPECT_NEAR(calib.baseline_m(), 0.5372, 1e-4);

  const fs::path real_path = real_datasets_dir() / "KITTI2012/training/calib/000070.txt";
  ASSERT_TRUE(real_data_present(real_path));
  const flexsight::KittiCalib real = flexsight::read_kitti_calib(real_path.string());
  EXPECT_EQ(real.focal_px(), 718.856);
  EXPECT_NEAR(real.baseline_m(), 0.5372, 1e-4);
}

TEST(Calibration, ReadsKittiRectifiedNames) {
  ScratchDir dir;
  const std::string path = dir.file("calib_cam_to_cam.txt");
  write_bytes(path,
              "calib_time: 09-Jan-2012 13:57:47\n"
              "S_rect_00: 1.242000e+03 3.750000e+02\n"
              "P_rect_00: 721.5 0 609.5 0 0 721.5 172.8 0 0 0 1 0\n"
              "P_rect_01: 721.5 0 609.5 -387.5 0 721.5 172.8 0 0 0 1 0\n");
  const flexsight::KittiCalib calib = flexsight::read_kitti_calib(path);
  EXPECT_EQ(calib.focal_px(), 721.5);
  EXPECT_EQ(calib.baseline_m(), 387.5 / 721.5);
}

TEST(Calibration, KittiRejectsMissingMatrixAndShortLines) {
  ScratchDir dir;
  const std::string no_p1 = dir.file("no_p1.txt");
  write_bytes(no_p1, "P0: 1 0 0 0 0 1 0 0 0 0 1 0\n");
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::read_kitti_calib(no_p1); }, no_p1, "missing 'P1'"));
  const std::string short_line = dir.file("short.txt");
  write_bytes(short_line, "P0: 1 0 0 0 0 1 0 0 0 0 1 0\nP1: 1 0 0 -1 0 1 0 0 0 0 1\n");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_kitti_calib(short_line); }, short_line,
                                 "line 'P1' has 11 numbers (expected 12"));
  const std::string bad_number = dir.file("bad_number.txt");
  write_bytes(bad_number, "P0: 1 0 0 0 0 1 0 0 0 0 1 zero\nP1: 1 0 0 -1 0 1 0 0 0 0 1 0\n");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_kitti_calib(bad_number); }, bad_number,
                                 "malformed number 'zero'"));
  const std::string middlebury = dir.file("calib.txt");
  write_bytes(middlebury, kMotorcycleCalib);
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_kitti_calib(middlebury); }, middlebury,
                                 "missing 'P0'"));
  const std::string missing = dir.file("missing.txt");
  EXPECT_TRUE(
      throws_input_error([&] { flexsight::read_kitti_calib(missing); }, missing, "does not exist"));
}

// Tests of the calibration readers (host/io/calibration.h): Middlebury calib.txt and
// KITTI calib files, with a clear InputError naming the file for missing keys and
// malformed values.
//
// The tests that check a format on synthetic files also read the real files of that
// format, from the datasets folder of tests/common/real_datasets.h; a missing real file
// fails them.
#include <gtest/gtest.h>

#include <array>
#include <sstream>
#include <string>

#include "host/io/calibration.h"
#include "host/io/image_io.h"
#include "tests/io/io_test_support.h"

using namespace flexsight::io_test_support;

namespace {

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

// Values no rectified pair can have are refused.
TEST(Calibration, MiddleburyRejectsWhatCannotBeARectifiedPair) {
  ScratchDir dir;
  struct Case {
    const char* key;
    const char* line;
    const char* problem;
  };
  const Case cases[] = {
      {"doffs", "doffs=1e300", "key 'doffs' is 1e+300, but cam1's cx - cam0's cx is 32.778"},
      {"doffs", "doffs=40", "key 'doffs' is 40"},
      {"cam1", "cam1=[1000 0 326.96; 0 1000 252.932; 0 0 1]", "key 'cam1' has focal length 1000, cam0 999.421"},
      {"cam1", "cam1=[999.421 0 326.96; 0 999.421 260; 0 0 1]", "key 'cam1' has its principal point on row 260"},
      {"cam0", "cam0=[999.421 0 294.182; 0 990 252.932; 0 0 1]", "key 'cam0' has fx 999.421 and fy 990"},
      {"cam0", "cam0=[999.421 1 294.182; 0 999.421 252.932; 0 0 1]", "key 'cam0' is not a pinhole matrix"},
      {"cam1", "cam1=[999.421 0 326.96; 0 999.421 252.932; 0 0 2]", "key 'cam1' is not a pinhole matrix"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.file(std::string("pair_") + c.key + ".txt");
    write_bytes(path, motorcycle_calib_with(c.key, c.line));
    EXPECT_TRUE(throws_input_error([&] { flexsight::read_middlebury_calib(path); }, path, c.problem)) << c.line;
  }
}

TEST(Calibration, KittiRejectsWhatCannotBeARectifiedPair) {
  ScratchDir dir;
  const std::string focal = dir.file("focal.txt");
  write_bytes(focal, "P0: 700 0 600 0 0 700 180 0 0 0 1 0\nP1: 720 0 600 -380 0 720 180 0 0 0 1 0\n");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_kitti_calib(focal); }, focal, "P1 has focal length 720, P0 700"));
  const std::string row = dir.file("row.txt");
  write_bytes(row, "P0: 700 0 600 0 0 700 180 0 0 0 1 0\nP1: 700 0 600 -380 0 700 190 0 0 0 1 0\n");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_kitti_calib(row); }, row, "principal point on row 190"));
  const std::string square = dir.file("square.txt");
  write_bytes(square, "P0: 700 0 600 0 0 650 180 0 0 0 1 0\nP1: 700 0 600 -380 0 650 180 0 0 0 1 0\n");
  EXPECT_TRUE(throws_input_error([&] { flexsight::read_kitti_calib(square); }, square, "P0 has fx 700 and fy 650"));
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

#pragma once
// Helpers shared by the dataset, report and eval command tests (tests/eval/): a scratch
// folder per test, and the files of a benchmark tree written by hand (text, PNG, PFM,
// Middlebury calib.txt, a whole MiddEval3 scene).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <system_error>

#include "tests/common/mat_rows.h"
#include "tests/common/real_datasets.h"

namespace flexsight::dataset_test_support {

namespace fs = std::filesystem;

inline constexpr float kInf = std::numeric_limits<float>::infinity();
inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// ---- fixtures on disk ------------------------------------------------------------

// A fresh folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device random;
    path_ = fs::temp_directory_path() /
            ("flexsight_" + std::string(info->name()) + "_" + std::to_string(random()));
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  fs::path operator/(const std::string& name) const { return path_ / name; }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

inline void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Little-endian PFM written byte by byte here, so the fixtures do not depend on the
// writer under test elsewhere. Rows are stored bottom-up.
inline void write_pfm_by_hand(const fs::path& path, const cv::Mat& image) {
  ASSERT_EQ(image.type(), CV_32FC1);
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << "Pf\n" << image.cols << " " << image.rows << "\n-1\n";
  for (int y = image.rows - 1; y >= 0; --y) {
    for (int x = 0; x < image.cols; ++x) {
      std::uint32_t bits = 0;
      const float value = image.at<float>(y, x);
      std::memcpy(&bits, &value, sizeof bits);
      for (int byte = 0; byte < 4; ++byte) out.put(static_cast<char>((bits >> (8 * byte)) & 0xff));
    }
  }
}

inline void write_png(const fs::path& path, const cv::Mat& image) {
  fs::create_directories(path.parent_path());
  ASSERT_TRUE(cv::imwrite(path.string(), image)) << path;
}

inline cv::Mat random_rgb(int width, int height, int seed) {
  cv::Mat image(height, width, CV_8UC3);
  cv::RNG(seed).fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

using testing_support::real_data_present;
using testing_support::real_datasets_dir;
using testing_support::rows_to_mask;
using testing_support::rows_to_mat;
using testing_support::rows_to_u16;

inline std::string middlebury_calib(int width, int height, int ndisp) {
  return "cam0=[100 0 " + std::to_string(width / 2) + "; 0 100 " + std::to_string(height / 2) +
         "; 0 0 1]\ncam1=[100 0 " + std::to_string(width / 2) + "; 0 100 " +
         std::to_string(height / 2) + "; 0 0 1]\ndoffs=0\nbaseline=100\nwidth=" +
         std::to_string(width) + "\nheight=" + std::to_string(height) + "\nndisp=" +
         std::to_string(ndisp) + "\nisint=0\nvmin=0\nvmax=" + std::to_string(ndisp - 1) + "\n";
}

// One MiddEval3 scene folder; images random, sizes taken from the ground truth.
inline void write_middeval3_scene(const fs::path& folder, const cv::Mat& gt,
                                  const cv::Mat& mask, int ndisp) {
  write_png(folder / "im0.png", random_rgb(gt.cols, gt.rows, 1));
  write_png(folder / "im1.png", random_rgb(gt.cols, gt.rows, 2));
  write_text(folder / "calib.txt", middlebury_calib(gt.cols, gt.rows, ndisp));
  write_pfm_by_hand(folder / "disp0GT.pfm", gt);
  write_png(folder / "mask0nocc.png", mask);
}

}  // namespace flexsight::dataset_test_support

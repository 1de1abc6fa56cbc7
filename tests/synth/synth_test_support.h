#pragma once
// What the synthetic-image tests share: the real T-LESS parts and backgrounds (read once
// per test program; a missing folder fails the test that needs it), a temporary folder,
// small fixture files, and geometry checks against a pose.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>

#include "host/dataset/annotated_image.h"
#include "host/dataset/gt_info.h"
#include "host/synth/background_library.h"
#include "host/synth/part_library.h"

namespace flexsight::testing_support {

// The folders CMake points at (../shared/detection by default; see datasets.md).
inline std::string tless_cad_folder() { return FLEXSIGHT_TLESS_CAD_DIR; }
inline std::string backgrounds_folder() { return FLEXSIGHT_BACKGROUNDS_DIR; }

inline ::testing::AssertionResult folder_present(const std::string& folder) {
  std::error_code error;
  if (std::filesystem::is_directory(folder, error)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << folder << " does not exist (FLEXSIGHT_DETECTION_DATA, ../shared/detection beside "
         << "the checkout by default)";
}

// The 23 T-LESS parts and the 300 backgrounds, loaded on first use and shared by every
// test (reading the meshes takes about half a second).
inline const PartLibrary& tless_parts() {
  static const PartLibrary library = PartLibrary::load_folder(tless_cad_folder());
  return library;
}
inline const BackgroundLibrary& real_backgrounds() {
  static const BackgroundLibrary library(backgrounds_folder());
  return library;
}

// A fresh folder, removed with everything in it when the object goes.
class TempFolder {
 public:
  TempFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device random;
    path_ = std::filesystem::temp_directory_path() /
            ("flexsight_synth_" + std::string(info->name()) + "_" + std::to_string(random()));
    std::filesystem::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  std::string str() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A tetrahedron with sides of about 10 mm, as OBJ text.
inline std::string tetrahedron_obj() {
  return "v 0 0 0\nv 10 0 0\nv 0 10 0\nv 0 0 10\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
}

// The flip matrix of an image (F = F^-1): the pose the renderer used is F times the
// stored one.
inline Eigen::Matrix3d flip_matrix(const AnnotatedImage& image) {
  return Eigen::Vector3d(image.flipped_horizontally ? -1.0 : 1.0,
                         image.flipped_vertically ? -1.0 : 1.0, 1.0)
      .asDiagonal();
}

}  // namespace flexsight::testing_support

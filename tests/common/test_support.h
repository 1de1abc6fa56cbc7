#pragma once
// Helpers shared by the matcher tests: fixture paths, synthetic images (random_texture.h),
// byte compares.
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <ostream>
#include <opencv2/core.hpp>
#include <random>
#include <string>
#include <vector>

#include "host/stereo/stereo_params.h"
#include "host/io/image_io.h"
#include "tests/common/random_texture.h"

namespace flexsight {
// Readable test parameter names in ctest output instead of raw bytes.
inline void PrintTo(StereoMethod method, std::ostream* os) { *os << method_name(method); }
}  // namespace flexsight

namespace flexsight::testing_support {

inline std::string fixture_dir() { return std::string(FLEXSIGHT_TEST_DATA_DIR) + "/TeddyH"; }

// A fresh, empty folder under the system temp dir for one test.
// The process id in the name: two checkouts (or two ctest runs) on one machine may run
// the same test at once, and must not remove each other's folders.
inline std::filesystem::path fresh_temp_dir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() /
             ("flexsight_test_" + name + "_" + std::to_string(static_cast<long>(::getpid())));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A 131x93 crop of the real fixture: odd sizes, real texture, quick to match.
struct FixtureCrop {
  cv::Mat left, right;
};

inline FixtureCrop fixture_crop() {
  StereoPair pair = load_stereo_pair(fixture_dir() + "/im0.png", fixture_dir() + "/im1.png");
  cv::Rect roi(40, 50, 131, 93);
  return {pair.left(roi).clone(), pair.right(roi).clone()};
}

inline bool same_bytes(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return false;
  cv::Mat ca = a.clone(), cb = b.clone();
  return std::memcmp(ca.data, cb.data, ca.total() * ca.elemSize()) == 0;
}

}  // namespace flexsight::testing_support

#pragma once
// Helpers shared by the stereo I/O tests (tests/io/test_*.cpp): a scratch folder per
// test, raw bytes in and out, PFM float bytes in a chosen order, and checks on the
// InputError a malformed file gives and on disparity maps.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <opencv2/core.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "host/io/input_error.h"
#include "tests/common/real_datasets.h"

namespace flexsight::io_test_support {

namespace fs = std::filesystem;
using flexsight::InputError;

inline constexpr float kInf = std::numeric_limits<float>::infinity();

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

inline void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  ASSERT_TRUE(out.good()) << path;
}

inline std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream contents;
  contents << in.rdbuf();
  return contents.str();
}

// Checks that `action` throws InputError whose message names `path` and contains
// `fragment`. Used as EXPECT_TRUE(throws_input_error(...)) so failures point at the call.
inline testing::AssertionResult throws_input_error(const std::function<void()>& action,
                                                   const std::string& path,
                                                   const std::string& fragment) {
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
inline std::string float_bytes(float value, bool little_endian) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  std::string out(4, '\0');
  for (int i = 0; i < 4; ++i) {
    const int shift = little_endian ? 8 * i : 8 * (3 - i);
    out[i] = static_cast<char>((bits >> shift) & 0xFFu);
  }
  return out;
}

inline std::string floats_le(const std::vector<float>& values) {
  std::string out;
  for (float v : values) out += float_bytes(v, true);
  return out;
}

using flexsight::testing_support::real_data_present;
using flexsight::testing_support::real_datasets_dir;

inline int count_inf(const cv::Mat& disparity) {
  int count = 0;
  for (int y = 0; y < disparity.rows; ++y) {
    for (int x = 0; x < disparity.cols; ++x) count += std::isinf(disparity.at<float>(y, x));
  }
  return count;
}

// Finite values of a disparity map all lie in (0, max_disparity].
inline bool finite_values_within(const cv::Mat& disparity, float max_disparity) {
  for (int y = 0; y < disparity.rows; ++y) {
    for (int x = 0; x < disparity.cols; ++x) {
      const float d = disparity.at<float>(y, x);
      if (std::isfinite(d) && !(d > 0 && d <= max_disparity)) return false;
      if (std::isnan(d)) return false;
    }
  }
  return true;
}

}  // namespace flexsight::io_test_support

#pragma once
// The real benchmark copies (MiddEval3-trainingQ/, middlebury-v2/, KITTI2012/; see
// datasets.md) that the I/O and dataset tests read besides their synthetic files. They
// are in ../shared/datasets beside the checkout, as for the scripts; the environment
// variable FLEXSIGHT_DATASETS names another folder laid out the same way. A missing file
// fails the test that reads it, with its path: a check that passed without its data
// would claim a format was read that never was.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace flexsight::testing_support {

inline std::filesystem::path real_datasets_dir() {
  const char* dir = std::getenv("FLEXSIGHT_DATASETS");
  if (dir != nullptr && *dir != '\0') return std::filesystem::path(dir);
  // FLEXSIGHT_TEST_DATA_DIR is <checkout>/tests/data.
  return (std::filesystem::path(FLEXSIGHT_TEST_DATA_DIR) / ".." / ".." / ".." / "shared" /
          "datasets")
      .lexically_normal();
}

// Success when `path` (a file or folder of the real datasets) exists; otherwise a
// failure that names it and where the datasets folder came from.
inline ::testing::AssertionResult real_data_present(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::exists(path, error)) return ::testing::AssertionSuccess();
  const char* dir = std::getenv("FLEXSIGHT_DATASETS");
  const bool from_env = dir != nullptr && *dir != '\0';
  return ::testing::AssertionFailure()
         << "real dataset path " << path << " does not exist (datasets folder "
         << real_datasets_dir()
         << (from_env ? ", from FLEXSIGHT_DATASETS" : ", ../shared/datasets beside the checkout")
         << "; see datasets.md)";
}

}  // namespace flexsight::testing_support

#pragma once
// Helpers of the `flexsight synth` tests: the options of a small, quick data set and
// the comparison of two output folders file by file, byte by byte.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "tests/cli/cli_test_support.h"

namespace flexsight::cli_test_support {

// The real T-LESS models and backgrounds (../shared/detection), small images.
inline std::string small_full_options(int max_parts = 3) {
  return std::string(" --cad ") + FLEXSIGHT_TLESS_CAD_DIR + " --backgrounds " +
         FLEXSIGHT_BACKGROUNDS_DIR + " --size 96x72 --max-parts " + std::to_string(max_parts);
}

// Every regular file under `root` by its path relative to root, with its bytes.
inline std::map<std::string, std::string> folder_bytes(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    files[fs::relative(entry.path(), root).string()] = bytes.str();
  }
  return files;
}

// Same files with the same bytes; names the first difference.
inline testing::AssertionResult same_folders(const fs::path& a, const fs::path& b) {
  const auto files_a = folder_bytes(a), files_b = folder_bytes(b);
  for (const auto& [name, bytes] : files_a) {
    const auto other = files_b.find(name);
    if (other == files_b.end()) return testing::AssertionFailure() << name << " only in " << a;
    if (other->second != bytes) return testing::AssertionFailure() << name << " differs";
  }
  for (const auto& [name, bytes] : files_b) {
    if (!files_a.count(name)) return testing::AssertionFailure() << name << " only in " << b;
  }
  if (files_a.empty()) return testing::AssertionFailure() << a << " is empty";
  return testing::AssertionSuccess() << files_a.size() << " files";
}

// Nothing under `dir` whose name says it is a staging folder or a temporary file.
inline testing::AssertionResult no_leftovers(const fs::path& dir) {
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".staging-") != std::string::npos || name.find(".tmp-") != std::string::npos) {
      return testing::AssertionFailure() << "left behind: " << entry.path();
    }
  }
  return testing::AssertionSuccess();
}

}  // namespace flexsight::cli_test_support

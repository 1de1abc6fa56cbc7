#pragma once
// What the dataset tests share: the rectangle images (rect_images.h), a scratch folder
// per test, every file of a folder tree as bytes, and a check on the InputError a bad
// input gives.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>

#include "host/io/input_error.h"
#include "tests/dataset/rect_images.h"

namespace flexsight::dataset_test_support {

namespace fs = std::filesystem;

// A fresh folder for the running test, under the test temp folder, with the pid so that
// parallel runs (ctest -j) stay apart; removed with the object.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::path(testing::TempDir()) /
            ("flexsight_dataset_" + std::string(info->test_suite_name()) + "_" + info->name() +
             "_" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  fs::path path_;
};

inline std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

inline void write_file(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// Every file under `root` with its bytes, and every folder (as "name/", no bytes), by
// path relative to `root`: two trees are equal when they have the same folders, empty
// ones too, and the same files with the same bytes.
inline std::map<std::string, std::string> tree_bytes(const fs::path& root) {
  std::map<std::string, std::string> entries;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string name = fs::relative(entry.path(), root).string();
    if (entry.is_directory()) entries[name + "/"] = "";
    if (entry.is_regular_file()) entries[name] = file_bytes(entry.path());
  }
  return entries;
}

// `action` throws InputError whose message contains `subject` and `fragment`.
inline testing::AssertionResult throws_input_error(const std::function<void()>& action,
                                                   const std::string& subject,
                                                   const std::string& fragment) {
  try {
    action();
  } catch (const InputError& e) {
    const std::string message = e.what();
    if (message.find(subject) == std::string::npos || message.find(fragment) == std::string::npos) {
      return testing::AssertionFailure()
             << "message lacks \"" << subject << "\" or \"" << fragment << "\": " << message;
    }
    return testing::AssertionSuccess();
  } catch (const std::exception& e) {
    return testing::AssertionFailure() << "threw another exception: " << e.what();
  }
  return testing::AssertionFailure() << "nothing thrown";
}

}  // namespace flexsight::dataset_test_support

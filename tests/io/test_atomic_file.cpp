// Tests of write_atomically (host/io/atomic_file.h): the file appears whole or not at
// all, the old file stays on failure, and a failed rename is an InputError.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/io/atomic_file.h"
#include "tests/io/io_test_support.h"

using namespace flexsight::io_test_support;

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

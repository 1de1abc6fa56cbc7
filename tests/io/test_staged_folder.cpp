// Tests of StagedFolder (host/io/staged_folder.h): the output folder appears whole at
// commit() or not at all, and a target that would be lost is refused up front.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "host/io/staged_folder.h"
#include "tests/io/io_test_support.h"

using namespace flexsight::io_test_support;
using flexsight::StagedFolder;

TEST(StagedFolder, AppearsOnlyAtCommit) {
  ScratchDir dir;
  const std::string target = dir.file("data");
  {
    StagedFolder staged(target, false);
    write_bytes(staged.path() + "/a.txt", "x");
    EXPECT_FALSE(fs::exists(target));
    staged.commit();
  }
  EXPECT_EQ(read_bytes(target + "/a.txt"), "x");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"data"});
}

TEST(StagedFolder, FailureLeavesNothing) {
  ScratchDir dir;
  { StagedFolder staged(dir.file("data"), false); write_bytes(staged.path() + "/a", "x"); }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(StagedFolder, RefusesNonEmptyTargetWithoutOverwrite) {
  ScratchDir dir;
  fs::create_directory(dir.file("data"));
  write_bytes(dir.file("data/old"), "old");
  EXPECT_TRUE(throws_input_error([&] { StagedFolder staged(dir.file("data"), false, "-o"); },
                                 dir.file("data"), "not empty; pass --overwrite"));
  EXPECT_EQ(read_bytes(dir.file("data/old")), "old");
}

TEST(StagedFolder, OverwriteReplacesAtCommitOnly) {
  ScratchDir dir;
  fs::create_directory(dir.file("data"));
  write_bytes(dir.file("data/old"), "old");
  {
    StagedFolder staged(dir.file("data"), true);
    write_bytes(staged.path() + "/new", "new");
    EXPECT_EQ(read_bytes(dir.file("data/old")), "old");  // still there until commit
    staged.commit();
  }
  EXPECT_FALSE(fs::exists(dir.file("data/old")));
  EXPECT_EQ(read_bytes(dir.file("data/new")), "new");
}

TEST(StagedFolder, EmptyTargetFolderIsAccepted) {
  ScratchDir dir;
  fs::create_directory(dir.file("data"));
  StagedFolder staged(dir.file("data/"), false);
  write_bytes(staged.path() + "/a", "a");
  staged.commit();
  EXPECT_EQ(read_bytes(dir.file("data/a")), "a");
}

TEST(StagedFolder, RefusesFileTargetAndMissingParent) {
  ScratchDir dir;
  write_bytes(dir.file("file"), "x");
  EXPECT_TRUE(throws_input_error([&] { StagedFolder staged(dir.file("file"), true); },
                                 dir.file("file"), "not a folder"));
  EXPECT_TRUE(throws_input_error([&] { StagedFolder staged(dir.file("no/such/data"), false); },
                                 dir.file("no/such/data"), "parent folder does not exist"));
}

// A run that dies (a crash, a kill) leaves its staging folder; the next run of the same
// target removes it when its process is gone, and leaves a live run's alone.
TEST(StagedFolder, RemovesStagingFoldersOfRunsThatDied) {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ASSERT_GT(child, 0);
  ::waitpid(child, nullptr, 0);  // its id now names no process
  ScratchDir dir;
  const std::string dead = ".data.staging-" + std::to_string(child);
  const std::string live = ".data.staging-" + std::to_string(::getppid());
  const std::string other = ".other.staging-" + std::to_string(child);
  for (const std::string& name : {dead, live, other}) {
    fs::create_directory(dir.file(name));
    write_bytes(dir.file(name + "/half"), "x");
  }
  {
    StagedFolder staged(dir.file("data"), false);
    EXPECT_FALSE(fs::exists(dir.file(dead)));
    EXPECT_TRUE(fs::exists(dir.file(live + "/half")));
    EXPECT_TRUE(fs::exists(dir.file(other + "/half")));
    staged.commit();
  }
}

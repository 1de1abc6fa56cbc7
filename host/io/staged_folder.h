#pragma once
// An output folder that appears whole or not at all: a run writes into a hidden
// staging folder beside the target and renames it into place when everything is
// written, so a failed or interrupted run never leaves a half-written data set under
// the name a user (or a merge) would take for a finished one. The folder-level
// counterpart of write_atomically (host/io/atomic_file.h).
#include <string>

namespace flexsight {

class StagedFolder {
 public:
  // Checks the target before any work starts: it must not exist, or be an empty
  // folder, or `overwrite` must be set (then it is replaced at commit()); its parent
  // folder must exist (it is not created: a typo in a path should not create a tree).
  // Removes the staging folders of the same target left by runs that died (their process
  // is gone), then creates this run's. Throws InputError naming `option` and `target`.
  StagedFolder(const std::string& target, bool overwrite, const std::string& option = "-o");
  // Removes the staging folder unless commit() succeeded.
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  // Where to write: ".NAME.staging-PID" beside the target, on the same file system.
  const std::string& path() const { return staging_; }
  const std::string& target() const { return target_; }
  // Replaces the target by the staging folder.
  void commit();

 private:
  std::string target_;
  std::string staging_;
  bool overwrite_;
  bool committed_ = false;
};

}  // namespace flexsight

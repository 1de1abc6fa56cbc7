#include "host/io/staged_folder.h"

#include <unistd.h>

#include <filesystem>
#include <system_error>

#include "host/io/input_error.h"

namespace flexsight {
namespace {
namespace fs = std::filesystem;
}  // namespace

StagedFolder::StagedFolder(const std::string& target, bool overwrite, const std::string& option)
    : target_(target), overwrite_(overwrite) {
  if (target.empty()) throw InputError("option " + option, "an output folder is required");
  fs::path path(target);
  if (path.filename().empty()) path = path.parent_path();  // "out/" names "out"
  target_ = path.string();
  std::error_code ec;
  if (fs::exists(path, ec)) {
    if (!fs::is_directory(path, ec)) {
      throw InputError(target_, "exists and is not a folder (option " + option + ")");
    }
    if (!overwrite && !fs::is_empty(path, ec)) {
      throw InputError(target_,
                       "exists and is not empty; pass --overwrite to replace it (option " + option +
                           ")");
    }
  }
  const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  if (!fs::is_directory(parent, ec)) {
    throw InputError(target_, "cannot be written: its parent folder does not exist");
  }
  staging_ = (parent / ("." + path.filename().string() + ".staging-" +
                        std::to_string(static_cast<long>(::getpid()))))
                 .string();
  fs::remove_all(staging_, ec);
  if (!fs::create_directory(staging_, ec)) {
    throw InputError(target_, "cannot be written: creating " + staging_ + " failed (" +
                                  ec.message() + ")");
  }
}

StagedFolder::~StagedFolder() {
  if (committed_) return;
  std::error_code ignored;
  fs::remove_all(staging_, ignored);
}

void StagedFolder::commit() {
  std::error_code ec;
  // The checks of the constructor are made again: another process may have written
  // the target meanwhile.
  if (fs::exists(target_, ec)) {
    if (!overwrite_ && !fs::is_empty(target_, ec)) {
      throw InputError(target_, "was written by someone else during the run; not replaced");
    }
    fs::remove_all(target_, ec);
    if (ec) throw InputError(target_, "cannot be replaced: " + ec.message());
  }
  fs::rename(staging_, target_, ec);
  if (ec) throw InputError(target_, "cannot be written (renaming the staging folder failed: " +
                                        ec.message() + ")");
  committed_ = true;
}

}  // namespace flexsight

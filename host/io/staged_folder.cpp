#include "host/io/staged_folder.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <system_error>

#include "host/io/input_error.h"

namespace flexsight {
namespace {
namespace fs = std::filesystem;

// True when no process has the id `pid` (kill with signal 0 only asks).
bool process_is_gone(long pid) {
  return pid > 0 && ::kill(static_cast<pid_t>(pid), 0) == -1 && errno == ESRCH;
}

// Removes the staging folders of `name` in `parent` that runs which died (a crash, a
// kill) left: ".NAME.staging-PID" whose PID is no longer running. A live run's folder
// stays, whoever it belongs to.
void remove_stale_staging(const fs::path& parent, const std::string& name) {
  const std::string prefix = "." + name + ".staging-";
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    if (entry.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string digits = entry.substr(prefix.size());
    if (digits.empty() || digits.size() > 9 ||
        digits.find_first_not_of("0123456789") != std::string::npos) {
      continue;
    }
    if (!process_is_gone(std::stol(digits))) continue;
    std::error_code ignored;
    fs::remove_all(it->path(), ignored);
  }
}

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
  remove_stale_staging(parent, path.filename().string());
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

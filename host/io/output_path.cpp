#include "host/io/output_path.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "host/io/input_error.h"

namespace flexsight {

namespace fs = std::filesystem;

void check_output_file(const std::string& path) {
  if (path.empty()) return;
  const std::string& subject = path;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(subject, "cannot be written: it is a folder");
  const fs::path parent = fs::path(path).parent_path();
  const fs::path folder = parent.empty() ? fs::path(".") : parent;
  const fs::file_status status = fs::status(folder, ec);
  if (!fs::exists(status)) throw InputError(subject, "cannot be written: its folder does not exist");
  if (!fs::is_directory(status)) {
    throw InputError(subject, "cannot be written: " + folder.string() + " is not a folder");
  }
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    throw InputError(subject, "cannot be written: its folder is not writable (" + std::string(std::strerror(errno)) + ")");
  }
}

}  // namespace flexsight

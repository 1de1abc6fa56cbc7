#include "host/io/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <system_error>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

namespace fs = std::filesystem;

// A hidden name next to the target, unique per process (pid) and per call (counter),
// e.g. "out/.disp.png.tmp-4242-0.png". It stays in the target's folder so the final
// rename never crosses a file system, and it keeps the target's extension because
// cv::imwrite chooses the encoder from the extension.
std::string temporary_path_for(const std::string& path) {
  static std::atomic<unsigned long> counter{0};
  const fs::path target(path);
  const std::string name = "." + target.filename().string() + ".tmp-" +
                           std::to_string(static_cast<long>(::getpid())) + "-" +
                           std::to_string(counter++) + target.extension().string();
  return (target.parent_path() / name).string();
}

void remove_quietly(const std::string& path) {
  std::error_code ignored;
  fs::remove(path, ignored);
}

}  // namespace

void write_atomically(const std::string& path,
                      const std::function<void(const std::string& tmp_path)>& write) {
  const std::string tmp_path = temporary_path_for(path);
  try {
    write(tmp_path);
  } catch (...) {
    remove_quietly(tmp_path);
    throw;
  }

  std::error_code ec;
  fs::rename(tmp_path, path, ec);
  if (ec) {
    remove_quietly(tmp_path);
    throw InputError(
        path, "cannot be written (renaming the temporary file failed: " + ec.message() + ")");
  }
}

}  // namespace flexsight

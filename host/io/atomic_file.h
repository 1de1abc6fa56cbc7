#pragma once
// Outputs are written under a temporary name in the target's folder and renamed into
// place, so a failure (or a crash) never leaves a partial file under the final name.
#include <functional>
#include <string>

namespace flexsight {

// Calls `write(tmp_path)`; on success renames tmp_path to `path`, on any exception
// removes tmp_path and rethrows. Throws InputError naming `path` when the rename fails.
void write_atomically(const std::string& path,
                      const std::function<void(const std::string& tmp_path)>& write);

}  // namespace flexsight

#include "host/sim/bin_folder.h"

#include <algorithm>

#include "host/io/input_error.h"

namespace flexsight {

namespace fs = std::filesystem;

BinFiles bin_files(const fs::path& dir, bool passive_stereo) {
  BinFiles files{dir.string(), (dir / "im0.png").string(), (dir / "im1.png").string(),
                 (dir / "im0_passive.png").string(), (dir / "im1_passive.png").string(),
                 (dir / "calib.txt").string()};
  std::vector<std::string> required = {files.left, files.right, files.calib, (dir / "disp0GT.pfm").string(),
                                       (dir / "mask0nocc.png").string(), (dir / "scene_gt.json").string(),
                                       (dir / "scene_gt_info.json").string()};
  if (passive_stereo) {
    required.push_back(files.left_passive);
    required.push_back(files.right_passive);
  }
  for (const std::string& file : required) {
    if (!fs::is_regular_file(file)) throw InputError(file, "is missing: not a synth-bin folder (or pass --pattern-only)");
  }
  if (!fs::is_regular_file(files.left_passive)) files.left_passive.clear();
  return files;
}

std::vector<fs::path> list_bin_dirs(const fs::path& bins_dir) {
  std::vector<fs::path> bin_dirs;
  for (const auto& entry : fs::directory_iterator(bins_dir)) {
    if (entry.is_directory() && fs::is_regular_file(entry.path() / "scene_gt.json")) bin_dirs.push_back(entry.path());
  }
  std::sort(bin_dirs.begin(), bin_dirs.end());
  return bin_dirs;
}

}  // namespace flexsight

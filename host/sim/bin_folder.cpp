#include "host/sim/bin_folder.h"

#include <algorithm>

#include "host/dataset/bop_layout.h"
#include "host/io/input_error.h"
#include "host/io/middeval3_files.h"

namespace flexsight {

namespace fs = std::filesystem;

BinFiles bin_files(const fs::path& dir, bool passive_stereo) {
  const MiddEval3Files scene = middeval3_files(dir);
  BinFiles files{dir.string(), scene.left, scene.right, scene.left_passive,
                 (dir / middeval3::kRightPassive).string(), scene.calib};
  std::vector<std::string> required = {files.left, files.right, files.calib, scene.left_truth,
                                       scene.nonocc_mask, (dir / bop_layout::kSceneGt).string(),
                                       (dir / bop_layout::kSceneGtInfo).string()};
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

#pragma once
// The layout of a folder of bins that `flexsight synth bin` writes (bin_writer.h): one
// scene folder per bin with the MiddEval3 pair, its passive twin, calib.txt,
// disp0GT.pfm, mask0nocc.png and the BOP ground truth. eval-pick reads it back.
#include <filesystem>
#include <string>
#include <vector>

namespace flexsight {

struct BinFiles {
  std::string dir, left, right, left_passive, right_passive, calib;
};

// The files of the bin in `dir`; InputError naming the first one missing (the passive
// pair is required only with `passive_stereo`). left_passive is empty when there is none.
BinFiles bin_files(const std::filesystem::path& dir, bool passive_stereo);

// The bins of `bins_dir`: its subfolders that hold a scene_gt.json, by name.
std::vector<std::filesystem::path> list_bin_dirs(const std::filesystem::path& bins_dir);

}  // namespace flexsight

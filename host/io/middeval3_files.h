#pragma once
// The files of one MiddEval3 scene folder (the Middlebury 2014 layout): what `flexsight eval`,
// `stereo` and `pick` read from a scene folder and what the bin simulator writes into one.
#include <filesystem>
#include <string>

namespace flexsight {

namespace middeval3 {
inline constexpr const char* kLeftImage = "im0.png";
inline constexpr const char* kRightImage = "im1.png";
inline constexpr const char* kCalib = "calib.txt";  // cam0, cam1, doffs, baseline, ..., ndisp
inline constexpr const char* kLeftTruth = "disp0GT.pfm";
inline constexpr const char* kRightTruth = "disp1GT.pfm";
inline constexpr const char* kNonoccMask = "mask0nocc.png";
// Not Middlebury's: the simulator's room-light-only views beside the projector's.
inline constexpr const char* kLeftPassive = "im0_passive.png";
inline constexpr const char* kRightPassive = "im1_passive.png";
}  // namespace middeval3

// Those files' paths in `folder` (folder / name), whether or not they exist.
struct MiddEval3Files {
  std::string left, right, calib, left_truth, nonocc_mask, left_passive;
};

inline MiddEval3Files middeval3_files(const std::filesystem::path& folder) {
  return {(folder / middeval3::kLeftImage).string(),  (folder / middeval3::kRightImage).string(),
          (folder / middeval3::kCalib).string(),      (folder / middeval3::kLeftTruth).string(),
          (folder / middeval3::kNonoccMask).string(), (folder / middeval3::kLeftPassive).string()};
}

}  // namespace flexsight

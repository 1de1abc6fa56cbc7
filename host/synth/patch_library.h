#pragma once
// Segmented patches of parts for the semi-synthetic generator: real pixels of a part
// (the paper cuts them from photographs of the parts) with the mask of where the part
// is. `flexsight synth patches` cuts them from any BOP folder with mask_visib.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace flexsight {

struct Patch {
  int obj_id = 0;
  std::string source;  // the file, for messages
  cv::Mat rgb;         // CV_8UC3, RGB order, cropped to the mask's box
  cv::Mat mask;        // CV_8UC1, 255 on the part, same size as rgb
};

// Every patch under `folder`, in sorted path order. A patch is an RGBA PNG whose alpha
// is the mask (alpha >= 128 is the part), or an image X.png / X.jpg with its mask
// X_mask.png beside it. Its object id is the number in the name of the folder that
// holds it (obj_000005/, obj_05/, 5/), the layout `synth patches` writes. Patches are
// small (a part's box), so all are kept in memory. Throws InputError naming the folder
// when it does not exist or holds no patch, and naming a file that cannot be decoded,
// has no mask, an empty mask, or sits in a folder whose name holds no object id.
std::vector<Patch> load_patch_library(const std::string& folder);

// The file name of patch `gt_id` of image (scene_id, im_id) in object `obj_id`'s
// folder: "obj_000005/000001_000042_000003.png", relative to the patches folder.
std::string patch_file_name(int obj_id, int scene_id, int im_id, int gt_id);

// Writes `rgb` (CV_8UC3, RGB) with `mask` as alpha to `path` as an RGBA PNG, atomically.
void write_patch(const std::string& path, const cv::Mat& rgb, const cv::Mat& mask);

}  // namespace flexsight

#pragma once
// Discovery of stereo benchmark scenes in the folder layouts of ../shared/datasets:
//   MiddEval3:      <root>/<Scene>/{im0.png, im1.png, calib.txt, disp0GT.pfm, mask0nocc.png}
//   Middlebury v2:  <root>/<scene>/{imL.png, imR.png, groundtruth.png, nonocc.png}
//   KITTI 2012:     <root>/training/{colored_0|image_0, colored_1|image_1, disp_occ, disp_noc}
//   KITTI 2015:     <root>/training/{image_2, image_3, disp_occ_0, disp_noc_0}
// <root> may also be a single MiddEval3 or v2 scene folder.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace flexsight {

enum class DatasetLayout { MiddEval3, MiddleburyV2, Kitti2012, Kitti2015 };

const char* layout_name(DatasetLayout layout);

struct Scene {
  std::string name;
  DatasetLayout layout = DatasetLayout::MiddEval3;
  std::string left_path;
  std::string right_path;
  std::string gt_path;      // ground-truth disparity of the left view ("" if none)
  std::string nonocc_path;  // MiddEval3 mask0nocc / v2 nonocc.png / KITTI disp_noc
  std::string calib_path;   // calib.txt or KITTI calib ("" if none)
  double gt_scale = 1.0;    // Middlebury v2 only: disparity = value / gt_scale
  int ndisp = 0;            // disparity search range (exclusive upper bound)
};

// Lists the scenes under `root`, sorted by name. ndisp: calib.txt for MiddEval3,
// 256 / gt_scale for v2 (tsukuba 16, venus 32, teddy and cones 64), 256 for KITTI.
// Throws InputError naming `root` if no known layout is found.
std::vector<Scene> discover_scenes(const std::string& root);

struct GroundTruth {
  cv::Mat disparity;  // CV_32FC1, +inf = unknown
  cv::Mat nonocc;     // CV_8UC1, 255 = non-occluded (KITTI: where disp_noc is valid)
};

// Throws InputError if the scene has no ground truth or a file is malformed.
GroundTruth load_ground_truth(const Scene& scene);

}  // namespace flexsight

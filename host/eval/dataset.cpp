#include "host/eval/dataset.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <system_error>

#include "host/io/calibration.h"
#include "host/io/input_error.h"
#include "host/io/kitti_disparity.h"
#include "host/io/middeval3_files.h"
#include "host/io/middlebury_v2.h"
#include "host/io/pfm.h"

namespace flexsight {

namespace fs = std::filesystem;

namespace {

bool is_file(const fs::path& path) {
  std::error_code ignored;
  return fs::is_regular_file(path, ignored);
}

bool is_dir(const fs::path& path) {
  std::error_code ignored;
  return fs::is_directory(path, ignored);
}

std::string if_exists(const fs::path& path) { return is_file(path) ? path.string() : ""; }

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// The name of a folder as the user means it: "data/Teddy/" and "data/Teddy/." are Teddy.
std::string folder_name(const fs::path& folder) {
  std::error_code error;
  fs::path canonical = fs::weakly_canonical(folder, error);
  if (error) canonical = fs::absolute(folder).lexically_normal();
  std::string name = canonical.filename().string();
  if (name.empty()) name = canonical.parent_path().filename().string();
  return name;
}

std::vector<fs::path> subfolders(const fs::path& root) {
  std::vector<fs::path> folders;
  std::error_code error;
  for (fs::directory_iterator it(root, error), end; !error && it != end; it.increment(error)) {
    if (is_dir(it->path())) folders.push_back(it->path());
  }
  if (error) throw InputError(root.string(), "cannot list folder: " + error.message());
  std::sort(folders.begin(), folders.end());
  return folders;
}

// A scene that is a folder of its own, named after it: its left and right images.
Scene folder_scene(const fs::path& folder, DatasetLayout layout, const char* left,
                   const char* right) {
  Scene scene;
  scene.name = folder_name(folder);
  scene.layout = layout;
  scene.left_path = (folder / left).string();
  scene.right_path = (folder / right).string();
  return scene;
}

// ---- MiddEval3 -------------------------------------------------------------------

bool is_middeval3_scene(const fs::path& folder) {
  const MiddEval3Files files = middeval3_files(folder);
  return is_file(files.left) && is_file(files.right) && is_file(files.calib);
}

Scene middeval3_scene(const fs::path& folder) {
  const MiddEval3Files files = middeval3_files(folder);
  Scene scene = folder_scene(folder, DatasetLayout::MiddEval3, middeval3::kLeftImage,
                             middeval3::kRightImage);
  scene.calib_path = files.calib;
  // The test split ships without ground truth; such scenes can still be matched.
  scene.gt_path = if_exists(files.left_truth);
  scene.nonocc_path = if_exists(files.nonocc_mask);
  scene.ndisp = read_middlebury_calib(scene.calib_path).ndisp;
  return scene;
}

// ---- Middlebury v2 ---------------------------------------------------------------

bool is_v2_scene(const fs::path& folder) {
  return is_file(folder / "imL.png") && is_file(folder / "imR.png");
}

// groundtruth.png stores disparity * scale, with a scale fixed per scene by the
// benchmark (chosen so the range fills the 8 bits).
double v2_scale(const std::string& scene_name) {
  const std::string name = lowercase(scene_name);
  if (name == "tsukuba") return 16.0;
  if (name == "venus") return 8.0;
  if (name == "teddy" || name == "cones") return 4.0;
  // Not one of the four evaluation scenes: assume 4, the scale of the 2003 scenes
  // (teddy, cones) that most other v2-style copies follow. A wrong guess shows up as
  // absurd error rates, not as a crash.
  return 4.0;
}

Scene v2_scene(const fs::path& folder) {
  Scene scene = folder_scene(folder, DatasetLayout::MiddleburyV2, "imL.png", "imR.png");
  scene.gt_path = if_exists(folder / "groundtruth.png");
  scene.nonocc_path = if_exists(folder / "nonocc.png");
  scene.gt_scale = v2_scale(scene.name);
  // The 8-bit encoding caps disparities below 256 / scale.
  scene.ndisp = static_cast<int>(std::lround(256.0 / scene.gt_scale));
  return scene;
}

// ---- KITTI -----------------------------------------------------------------------

struct KittiFolders {
  DatasetLayout layout;
  const char* left;
  const char* right;
  const char* occ;
  const char* noc;
  const char* calib;
};

// The colour images of KITTI 2012 are preferred when present: the matcher's support
// weights work on colour differences.
std::optional<KittiFolders> kitti_folders(const fs::path& training) {
  if (is_dir(training / "image_2") && is_dir(training / "image_3")) {
    return KittiFolders{DatasetLayout::Kitti2015, "image_2", "image_3", "disp_occ_0",
                        "disp_noc_0", "calib_cam_to_cam"};
  }
  if (is_dir(training / "colored_0") && is_dir(training / "colored_1")) {
    return KittiFolders{DatasetLayout::Kitti2012, "colored_0", "colored_1", "disp_occ",
                        "disp_noc", "calib"};
  }
  if (is_dir(training / "image_0") && is_dir(training / "image_1")) {
    return KittiFolders{DatasetLayout::Kitti2012, "image_0", "image_1", "disp_occ",
                        "disp_noc", "calib"};
  }
  return std::nullopt;
}

// KITTI names pairs "000070_10.png"; only frame _10 has ground truth, so only those
// pairs are scenes. Calibration is per sequence: calib/000070.txt.
std::vector<Scene> kitti_scenes(const fs::path& training, const KittiFolders& folders) {
  std::vector<Scene> scenes;
  std::error_code error;
  const fs::path left_dir = training / folders.left;
  for (fs::directory_iterator it(left_dir, error), end; !error && it != end; it.increment(error)) {
    const fs::path left = it->path();
    const std::string stem = left.stem().string();
    if (left.extension() != ".png" || stem.size() < 3 || stem.substr(stem.size() - 3) != "_10") {
      continue;
    }
    const fs::path right = training / folders.right / left.filename();
    if (!is_file(right)) continue;
    Scene scene;
    scene.name = stem;
    scene.layout = folders.layout;
    scene.left_path = left.string();
    scene.right_path = right.string();
    scene.gt_path = if_exists(training / folders.occ / left.filename());
    scene.nonocc_path = if_exists(training / folders.noc / left.filename());
    scene.calib_path = if_exists(training / folders.calib / (stem.substr(0, stem.size() - 3) + ".txt"));
    scene.ndisp = 256;  // KITTI disparities stay well below 256 px
    scenes.push_back(std::move(scene));
  }
  if (error) throw InputError(left_dir.string(), "cannot list folder: " + error.message());
  return scenes;
}

// `root` may be the KITTI folder holding training/, or training/ itself.
std::vector<Scene> discover_kitti(const fs::path& root) {
  for (const fs::path& training : {root / "training", root}) {
    if (auto folders = kitti_folders(training)) return kitti_scenes(training, *folders);
  }
  return {};
}

// ---- ground truth ----------------------------------------------------------------

cv::Mat load_mask_matching(const std::string& path, const cv::Mat& ground_truth) {
  cv::Mat mask = read_mask(path);
  if (mask.size() != ground_truth.size()) {
    throw InputError(path, "mask is " + std::to_string(mask.cols) + "x" +
                               std::to_string(mask.rows) + " but the ground truth is " +
                               std::to_string(ground_truth.cols) + "x" +
                               std::to_string(ground_truth.rows));
  }
  return mask;
}

// KITTI has no occlusion mask: the non-occluded ground truth is a second, sparser map,
// and a pixel is non-occluded where that map has a value.
cv::Mat kitti_nonocc_mask(const std::string& noc_path, const cv::Mat& ground_truth) {
  const cv::Mat noc = read_kitti_disparity(noc_path);
  if (noc.size() != ground_truth.size()) {
    throw InputError(noc_path, "differs in size from the ground truth");
  }
  cv::Mat mask(noc.size(), CV_8UC1);
  for (int y = 0; y < noc.rows; ++y) {
    const float* d = noc.ptr<float>(y);
    uchar* m = mask.ptr<uchar>(y);
    for (int x = 0; x < noc.cols; ++x) m[x] = std::isfinite(d[x]) ? 255 : 0;
  }
  return mask;
}

cv::Mat read_pfm_disparity(const std::string& path) {
  cv::Mat disparity = read_pfm(path);
  if (disparity.type() != CV_32FC1) throw InputError(path, "expected a one-channel PFM (Pf)");
  return disparity;
}

}  // namespace

const char* layout_name(DatasetLayout layout) {
  switch (layout) {
    case DatasetLayout::MiddEval3: return "MiddEval3";
    case DatasetLayout::MiddleburyV2: return "Middlebury v2";
    case DatasetLayout::Kitti2012: return "KITTI 2012";
    case DatasetLayout::Kitti2015: return "KITTI 2015";
  }
  return "unknown";
}

std::vector<Scene> discover_scenes(const std::string& root) {
  const fs::path root_path(root);
  if (!is_dir(root_path)) throw InputError(root, "no such folder");

  // A single scene folder.
  if (is_middeval3_scene(root_path)) return {middeval3_scene(root_path)};
  if (is_v2_scene(root_path)) return {v2_scene(root_path)};

  std::vector<Scene> scenes = discover_kitti(root_path);
  if (scenes.empty()) {
    // A folder of MiddEval3 and/or v2 scenes; other subfolders are ignored.
    for (const fs::path& folder : subfolders(root_path)) {
      if (is_middeval3_scene(folder)) {
        scenes.push_back(middeval3_scene(folder));
      } else if (is_v2_scene(folder)) {
        scenes.push_back(v2_scene(folder));
      }
    }
  }
  if (scenes.empty()) {
    throw InputError(root, "no stereo scenes found (expected a MiddEval3, Middlebury v2 or "
                           "KITTI training layout, or a single scene folder)");
  }
  std::sort(scenes.begin(), scenes.end(),
            [](const Scene& a, const Scene& b) { return a.name < b.name; });
  return scenes;
}

GroundTruth load_ground_truth(const Scene& scene) {
  if (scene.gt_path.empty()) throw InputError(scene.name, "scene has no ground truth");
  GroundTruth truth;
  switch (scene.layout) {
    case DatasetLayout::MiddEval3:
      truth.disparity = read_pfm_disparity(scene.gt_path);
      break;
    case DatasetLayout::MiddleburyV2:
      truth.disparity = read_middlebury_v2_disparity(scene.gt_path, scene.gt_scale);
      break;
    case DatasetLayout::Kitti2012:
    case DatasetLayout::Kitti2015:
      truth.disparity = read_kitti_disparity(scene.gt_path);
      break;
  }
  if (scene.nonocc_path.empty()) return truth;  // evaluation treats every pixel as non-occluded
  const bool kitti = scene.layout == DatasetLayout::Kitti2012 ||
                     scene.layout == DatasetLayout::Kitti2015;
  truth.nonocc = kitti ? kitti_nonocc_mask(scene.nonocc_path, truth.disparity)
                       : load_mask_matching(scene.nonocc_path, truth.disparity);
  return truth;
}

}  // namespace flexsight

#pragma once
// Where the files of a BOP scene lie, relative to the split folder that holds the scene
// folders (docs/dataset.md). One definition for the writer, the readers and the merge.
#include <cstdio>
#include <string>

namespace flexsight::bop_layout {

// Six digits, zero-padded, as BOP names scenes, images and ground-truth indices (wider
// numbers keep all their digits).
inline std::string six_digits(long long value) {
  char text[32];
  std::snprintf(text, sizeof text, "%06lld", value);
  return text;
}

inline std::string scene_dir(int scene_id) { return six_digits(scene_id); }

// Paths inside a scene folder.
inline std::string rgb_in_scene(int im_id, const std::string& extension) {
  return "rgb/" + six_digits(im_id) + "." + extension;
}
inline std::string depth_in_scene(int im_id) { return "depth/" + six_digits(im_id) + ".png"; }
// mask/ holds the amodal masks, mask_visib/ the visible ones: <im_id>_<gt_id>.png.
inline std::string mask_in_scene(int im_id, int gt_id, bool visible) {
  return std::string(visible ? "mask_visib/" : "mask/") + six_digits(im_id) + "_" +
         six_digits(gt_id) + ".png";
}

// Paths inside the split folder. rgb_file is the COCO file's file_name for the image:
// "000001/rgb/000042.jpg".
inline std::string rgb_file(int scene_id, int im_id, const std::string& extension) {
  return scene_dir(scene_id) + "/" + rgb_in_scene(im_id, extension);
}
inline std::string depth_file(int scene_id, int im_id) {
  return scene_dir(scene_id) + "/" + depth_in_scene(im_id);
}
inline std::string mask_file(int scene_id, int im_id, int gt_id, bool visible) {
  return scene_dir(scene_id) + "/" + mask_in_scene(im_id, gt_id, visible);
}

// The per-scene JSON files, in the scene folder.
inline constexpr const char* kSceneCamera = "scene_camera.json";
inline constexpr const char* kSceneGt = "scene_gt.json";
inline constexpr const char* kSceneGtInfo = "scene_gt_info.json";

// The dataset writer's own files, at the root beside the scene folders.
inline constexpr const char* kCocoFile = "coco_instances.json";
inline constexpr const char* kDatasetInfo = "dataset_info.json";

}  // namespace flexsight::bop_layout

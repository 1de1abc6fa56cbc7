#pragma once
// A BOP scene's three JSON files (scene_camera.json, scene_gt.json, scene_gt_info.json),
// written from and read into the fields of AnnotatedImage. The writer and the merge both
// write through write_bop_scene_json, so a merge gives the bytes a single run gives:
//   * images in numeric im_id order, one line per image (per part for the lists);
//   * keys of each entry in alphabetical order (as the BOP toolkit's sort_keys);
//   * doubles as the shortest text that reads back to the same double (nlohmann-json),
//     so reading a file and writing it again reproduces it.
#include <map>
#include <string>
#include <vector>

#include "host/dataset/annotated_image.h"

namespace flexsight {

// What the JSON files say about one image: camera, and each part's pose and gt_info
// numbers (masks stay empty).
struct BopImageRecord {
  DatasetCamera camera;
  std::vector<PartAnnotation> parts;
};

// A scene's records by im_id.
using BopSceneRecords = std::map<int, BopImageRecord>;

// Writes the three files into `scene_dir` (which must exist), each atomically.
void write_bop_scene_json(const std::string& scene_dir, const BopSceneRecords& records);

struct BopSceneJson {
  BopSceneRecords images;
  bool has_gt_info = false;  // scene_gt_info.json was there (else boxes and counts unset)
};

// Reads `scene_dir`'s JSON files. scene_camera.json and scene_gt.json are required,
// scene_gt_info.json is read when present. Keys of scene_camera entries other than cam_K
// and depth_scale go to DatasetCamera::extra; depth_scale may be absent only when
// `require_depth_scale` is false (it then keeps its default). Throws InputError naming
// the file for a missing or invalid file, a missing key, a value of the wrong type or
// length, images listed in one file but not in another, and a pose, camera or box out
// of its physical range (host/io/physical_checks.h; a reflected R where the image is
// flipped once, a t at the origin where its camera entry says "pose_unknown").
BopSceneJson read_bop_scene_json(const std::string& scene_dir, bool require_depth_scale);

}  // namespace flexsight

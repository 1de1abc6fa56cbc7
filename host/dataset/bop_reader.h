#pragma once
// Reads BOP data as the BOP toolkit lays it out (docs/dataset.md): a scene folder
// (scene_camera.json, scene_gt.json, optional scene_gt_info.json, rgb/ or gray/, optional
// depth/, mask/, mask_visib/) or a split folder of such scene folders, ours or the real
// T-LESS ones unchanged. The JSON files are read and checked when the reader is made;
// images are read one at a time by load().
#include <string>
#include <vector>

#include "host/dataset/annotated_image.h"
#include "host/dataset/bop_json.h"

namespace flexsight {

struct BopImageRef {
  int scene_id = 0;
  int im_id = 0;
};

class BopReader {
 public:
  // `path`: a scene folder (it holds scene_camera.json) or a split folder (its
  // subfolders that hold one are the scenes; other entries are ignored). A scene's id is
  // its folder's name read as a number (0 when the name is not one). Throws InputError
  // for a path that is neither, and for any malformed JSON file (bop_json.h).
  explicit BopReader(const std::string& path);

  // Images in (scene_id, im_id) order.
  std::size_t size() const { return index_.size(); }
  BopImageRef ref(std::size_t i) const;
  // What the JSON files say about image i (poses, boxes, pixel counts; no image is read),
  // for evaluators that need the annotations only.
  const BopImageRecord& record(std::size_t i) const;
  // The folder of image i's scene, and whether it has scene_gt_info.json (without it the
  // records' boxes and counts are unset).
  const std::string& scene_dir(std::size_t i) const;
  bool has_gt_info(std::size_t i) const;

  // Image i: rgb (rgb/ or gray/, .png, .jpg, .jpeg or .tif; gray and 16-bit converted to
  // 8-bit RGB), depth in mm (value * depth_scale) when the scene has depth/, masks when it
  // has mask/ or mask_visib/ (any non-zero value is the part: 255), and the JSON
  // records. Throws InputError naming the file for a missing or unreadable image, a depth
  // that is not 16-bit gray, a mask that is not 8-bit gray, a size that differs from
  // the rgb's, or a bbox_visib that reaches beyond the image. Thread-safe.
  AnnotatedImage load(std::size_t i) const;

  // For the up-front pass of a command that will load image i: its size read from its
  // file's header (image_header.h), and every bbox_visib of scene_gt_info.json checked to
  // lie inside it, the error naming that file as load() would. `require_image`: a missing
  // image is an error; otherwise (a command that only scores boxes) it is skipped.
  // Returns the image's size (empty when it was skipped or the scene has no
  // scene_gt_info.json).
  cv::Size check_boxes_inside_image(std::size_t i, bool require_image) const;

 private:
  struct Scene {
    std::string dir;
    int scene_id = 0;
    BopSceneJson json;
    bool has_depth = false, has_mask = false, has_mask_visib = false;
  };
  struct Entry {
    std::size_t scene = 0;
    int im_id = 0;
  };
  void add_scene(const std::string& dir);

  std::vector<Scene> scenes_;
  std::vector<Entry> index_;
};

}  // namespace flexsight

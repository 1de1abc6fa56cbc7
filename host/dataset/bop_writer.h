#pragma once
// Writes annotated images as a BOP split folder (docs/dataset.md): per scene,
// rgb/<im_id>.jpg|png, depth/<im_id>.png, mask/ and mask_visib/<im_id>_<gt_id>.png as the
// images arrive, and scene_camera.json, scene_gt.json and scene_gt_info.json at finish().
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "host/dataset/annotated_image.h"
#include "host/dataset/bop_json.h"

namespace flexsight {

struct BopWriterOptions {
  enum class RgbFormat { jpg, png };
  // JPEG keeps a training set of thousands of images small; PNG is lossless.
  RgbFormat rgb_format = RgbFormat::jpg;
  // JPEG quality (1..100). 95 leaves no block artefacts a detector could learn from.
  int jpg_quality = 95;
  // Write depth/ (16-bit PNG, value = round(depth_mm / depth_scale)). Off for sets that
  // train an RGB detector only: depth PNGs are the largest files.
  bool write_depth = true;
  // Write mask/ and mask_visib/ (8-bit PNG, 255 on the part). The COCO file carries the
  // visible masks anyway, as RLE.
  bool write_masks = true;

  // Throws InputError ("bop options: ...") for a quality outside 1..100.
  void check() const;
  // "jpg" or "png".
  std::string rgb_extension() const;
  // The folders each scene gets: rgb, and depth, mask, mask_visib as set. The merge
  // makes the same ones, so that its output has the writer's folders, empty ones too.
  std::vector<std::string> scene_folders() const;
};

class BopWriter {
 public:
  // Writes into `root` (the split folder; created when missing).
  BopWriter(std::string root, BopWriterOptions options);

  // Checks `image` and writes its image files. Safe to call from several threads at once,
  // in any order of images. Throws InputError naming the file concerned for: an image
  // (scene_id, im_id) written before, rgb not 8-bit gray or RGB, depth (when written)
  // missing or not CV_32FC1 of the rgb's size, a depth that is negative, not finite or
  // beyond 65535 * depth_scale (no clamping: a wrong depth would teach a wrong pose;
  // raise depth_scale instead), masks (when written) missing or not CV_8UC1 of the rgb's
  // size, a pose or camera that is not finite, depth_scale <= 0, or camera.extra that is
  // not an object or names cam_K or depth_scale. When a check fails nothing is written;
  // when writing a file fails, the image is not recorded (the JSON files will not list it).
  void write(const AnnotatedImage& image);

  // Writes every scene's JSON files. Call once, after the last write().
  void finish();

  // The images written so far, by scene.
  std::map<int, BopSceneRecords> records() const;
  const BopWriterOptions& options() const { return options_; }

 private:
  void check_and_reserve(const AnnotatedImage& image);

  std::string root_;
  BopWriterOptions options_;
  mutable std::mutex mutex_;
  std::set<std::pair<int, int>> reserved_;  // (scene_id, im_id) being written or written
  std::set<int> scene_dirs_made_;
  std::map<int, BopSceneRecords> scenes_;
  bool finished_ = false;
};

}  // namespace flexsight

#pragma once
// The content of a COCO instances file, as the COCO writer takes it and the reader gives
// it back (docs/dataset.md has the file's layout).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "host/dataset/coco_rle.h"

namespace flexsight {

struct CocoImage {
  std::int64_t id = 0;    // the caller's global image index
  std::string file_name;  // relative to the COCO file's folder: "000001/rgb/000042.jpg"
  int width = 0, height = 0;
  // The BOP image this entry describes (extra keys of ours; -1 when a file lacks them).
  int scene_id = -1, im_id = -1;
};

struct CocoAnnotation {
  std::int64_t id = 0;  // numbered 1, 2, ... in (image id, gt_id) order when written
  std::int64_t image_id = 0;
  int category_id = 0;           // the part's obj_id
  std::array<double, 4> bbox{};  // x, y, w, h of the visible mask (pixels)
  double area = 0;               // pixels of the visible mask
  int iscrowd = 0;
  CocoRle segmentation;  // the visible mask
};

struct CocoCategory {
  int id = 0;
  std::string name;  // "obj_01" unless given
  std::string supercategory = "part";
  bool operator==(const CocoCategory& other) const {
    return id == other.id && name == other.name && supercategory == other.supercategory;
  }
};

struct CocoDataset {
  std::vector<CocoImage> images;
  std::vector<CocoAnnotation> annotations;
  std::vector<CocoCategory> categories;
};

}  // namespace flexsight

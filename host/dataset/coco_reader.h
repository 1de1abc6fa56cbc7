#pragma once
// Reads a COCO instances file (ours, or another tool's with RLE segmentations) and the
// images it points at.
#include <string>
#include <vector>

#include "host/dataset/annotated_image.h"
#include "host/dataset/coco_dataset.h"

namespace flexsight {

// Reads `path`: images, annotations and categories, each entry checked (ids, sizes,
// bbox of 4 numbers, an RLE whose counts cover size[0] x size[1] pixels equal to the
// image's height x width). Segmentations may be compressed RLE ({"size", "counts":
// string}, as pycocotools writes) or uncompressed RLE ("counts": list of integers, as
// COCO's crowd regions are). Polygons are refused: rasterising them as pycocotools does
// would need its own polygon filler, and no file this project reads has them. Throws
// InputError naming `path` and the entry for any malformed content, a duplicate image
// id, or an annotation of an image or category not listed.
CocoDataset read_coco(const std::string& path);

// A COCO file and its images, loaded one at a time.
class CocoReader {
 public:
  // Reads the file (read_coco) and indexes the annotations by image.
  explicit CocoReader(std::string path);

  const CocoDataset& dataset() const { return dataset_; }
  std::size_t size() const { return dataset_.images.size(); }

  // Image `index` (in the file's order) as an AnnotatedImage: rgb read from file_name
  // relative to the COCO file's folder (RGB order), one part per annotation of the image
  // in file order (obj_id = category_id, mask_visib decoded, bbox_visib and
  // px_count_visib from it; pose, amodal mask and depth unknown), scene_id and im_id
  // from the entry (or 0 and the image id when the file lacks them). Throws InputError
  // for an unreadable image or one whose size differs from the entry's. Thread-safe.
  AnnotatedImage load(std::size_t index) const;

  // For the up-front pass of a command that will load image `index`: its size read from
  // its file's header (image_header.h) checked against the file's width and height (the
  // annotations were checked against those when the file was read), the error naming
  // the image as load() would. `require_image`: a missing image is an error; otherwise
  // (a command that only scores boxes) it is skipped. Returns the size (empty when skipped).
  cv::Size check_image_size(std::size_t index, bool require_image) const;

 private:
  std::string image_path(std::size_t index) const;
  void require_entry_size(std::size_t index, const cv::Size& size) const;

  std::string path_;
  CocoDataset dataset_;
  std::vector<std::vector<std::size_t>> annotations_of_image_;  // by image index
};

}  // namespace flexsight

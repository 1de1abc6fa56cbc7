#pragma once
// Collects the images and visible-mask annotations of a data set and writes them as one
// COCO instances file. Images are sorted by id and annotations numbered 1, 2, ... in
// (image id, gt_id) order when the file is written, so the file depends only on the set
// of images, not on the order or the threads that added them, and a merge of shards
// gives the bytes of a single run.
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "host/dataset/annotated_image.h"
#include "host/dataset/coco_dataset.h"

namespace flexsight {

// "obj_01" for obj_id 1: the name of a category nobody named.
std::string default_category_name(int obj_id);

// The annotations of `image`'s parts (category = obj_id, in gt_id order) from their
// visible masks; parts without a visible pixel get none. Throws InputError naming
// `subject` when a part's mask_visib is not CV_8UC1 of the rgb's size.
std::vector<CocoAnnotation> coco_annotations_of(const AnnotatedImage& image, std::int64_t image_id,
                                                const std::string& subject);

class CocoWriter {
 public:
  // `path`: the file finish() writes. `categories`: the fixed list (every annotation's
  // category must be in it), or empty to list the categories the annotations use, named
  // by default_category_name.
  CocoWriter(std::string path, std::vector<CocoCategory> categories);

  // Throws InputError naming the file when an annotation's category is not in the fixed
  // list. Thread-safe.
  void check_categories(const std::vector<CocoAnnotation>& annotations) const;

  // Adds an image with its annotations (their ids are ignored). Thread-safe. Throws
  // InputError naming the file for an image id added before or a category not listed.
  void add(const CocoImage& image, std::vector<CocoAnnotation> annotations);

  // Adds a category to the derived list (a merge passes on its shards' lists; a name
  // that differs from an earlier one for the same id is an InputError).
  void add_category(const CocoCategory& category);

  // The file's text, as finish() writes it.
  std::string text() const;
  void finish() const;

  std::size_t image_count() const;

 private:
  std::string path_;
  bool fixed_categories_;
  mutable std::mutex mutex_;
  std::map<int, CocoCategory> categories_;
  std::map<std::int64_t, std::pair<CocoImage, std::vector<CocoAnnotation>>> images_;
};

}  // namespace flexsight

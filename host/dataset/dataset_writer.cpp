#include "host/dataset/dataset_writer.h"

#include "host/dataset/bop_layout.h"
#include "host/dataset/dataset_files.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

// The folder must be empty before BopWriter creates anything in it.
const std::string& empty_root(const std::string& root) {
  dataset_files::create_empty_directory(root);
  return root;
}

}  // namespace

DatasetWriter::DatasetWriter(const std::string& root, DatasetWriterOptions options)
    : root_(empty_root(root)),
      options_(std::move(options)),
      bop_(root_, options_.bop),
      coco_(root_ + "/" + bop_layout::kCocoFile, options_.categories) {}

void DatasetWriter::add(const AnnotatedImage& image, std::int64_t image_index) {
  const std::string coco_path = root_ + "/" + bop_layout::kCocoFile;
  // Everything that can be refused is checked before the first file is written.
  std::vector<CocoAnnotation> annotations = coco_annotations_of(
      image, image_index,
      root_ + "/" +
          bop_layout::rgb_file(image.scene_id, image.im_id, options_.bop.rgb_extension()));
  coco_.check_categories(annotations);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!indices_.insert(image_index).second) {
      throw InputError(coco_path, "image index " + std::to_string(image_index) + " is added twice");
    }
  }
  try {
    bop_.write(image);
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    indices_.erase(image_index);
    throw;
  }
  CocoImage entry;
  entry.id = image_index;
  entry.file_name = bop_layout::rgb_file(image.scene_id, image.im_id, options_.bop.rgb_extension());
  entry.width = image.rgb.cols;
  entry.height = image.rgb.rows;
  entry.scene_id = image.scene_id;
  entry.im_id = image.im_id;
  coco_.add(entry, std::move(annotations));
}

void DatasetWriter::finish() {
  bop_.finish();
  coco_.finish();
  DatasetInfo info;
  info.options = options_;
  info.image_count = static_cast<std::int64_t>(coco_.image_count());
  dataset_files::write_text(root_ + "/" + bop_layout::kDatasetInfo, dataset_info_text(info));
}

}  // namespace flexsight

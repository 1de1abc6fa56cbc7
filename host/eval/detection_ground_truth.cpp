#include "host/eval/detection_ground_truth.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <numeric>
#include <set>

#include "host/dataset/bop_layout.h"
#include "host/dataset/bop_reader.h"
#include "host/dataset/coco_reader.h"
#include "host/dataset/coco_writer.h"
#include "host/dataset/dataset_files.h"
#include "host/io/input_error.h"

namespace flexsight {

DetectionGroundTruth::DetectionGroundTruth(const std::string& path, double min_visible_fraction) {
  namespace fs = std::filesystem;
  const std::string coco_in_folder = (fs::path(path) / bop_layout::kCocoFile).string();
  const bool coco = dataset_files::is_file(path) || dataset_files::is_file(coco_in_folder);
  if (coco && min_visible_fraction > 0) {
    throw InputError(path, "is a COCO data set, which has no visible fraction of a part "
                           "(--min-visible needs a BOP folder)");
  }
  if (dataset_files::is_file(path)) {
    read_coco_file(path);
  } else if (dataset_files::is_file(coco_in_folder)) {
    read_coco_file(coco_in_folder);
  } else if (dataset_files::is_directory(path)) {
    read_bop_folder(path, min_visible_fraction);
  } else {
    throw InputError(path, "does not exist (expected a COCO instances file, a folder with " +
                               std::string(bop_layout::kCocoFile) + ", or a BOP folder)");
  }
}

DetectionGroundTruth::~DetectionGroundTruth() = default;
DetectionGroundTruth::DetectionGroundTruth(DetectionGroundTruth&&) noexcept = default;

void DetectionGroundTruth::read_coco_file(const std::string& path) {
  format_ = Format::coco;
  source_ = path;
  coco_ = std::make_unique<CocoReader>(path);
  const CocoDataset& dataset = coco_->dataset();
  // COCOeval visits images in ascending id, which decides the order of equal scores.
  reader_index_.resize(dataset.images.size());
  std::iota(reader_index_.begin(), reader_index_.end(), std::size_t{0});
  std::sort(reader_index_.begin(), reader_index_.end(), [&](std::size_t a, std::size_t b) {
    return dataset.images[a].id < dataset.images[b].id;
  });
  for (std::size_t i = 0; i < reader_index_.size(); ++i) {
    const CocoImage& entry = dataset.images[reader_index_[i]];
    DetectionImage image;
    image.coco_id = entry.id;
    image.scene_id = entry.scene_id;
    image.im_id = entry.im_id;
    images_.push_back(std::move(image));
  }
  std::map<std::int64_t, std::size_t> image_of_id;
  for (std::size_t i = 0; i < images_.size(); ++i) image_of_id[images_[i].coco_id] = i;
  std::set<int> used_categories;
  for (const CocoAnnotation& annotation : dataset.annotations) {
    TruthBox box;
    box.category_id = annotation.category_id;
    box.bbox = annotation.bbox;
    box.area = annotation.area;
    box.crowd = annotation.iscrowd != 0;
    images_[image_of_id.at(annotation.image_id)].truth.push_back(box);
    used_categories.insert(annotation.category_id);
  }
  for (const CocoCategory& category : dataset.categories) {
    categories_.push_back({category.id, category.name});
  }
  if (categories_.empty()) {
    for (int id : used_categories) categories_.push_back({id, default_category_name(id)});
  }
  std::sort(categories_.begin(), categories_.end(),
            [](const DetectionCategory& a, const DetectionCategory& b) { return a.id < b.id; });
  for (std::size_t c = 1; c < categories_.size(); ++c) {
    if (categories_[c].id == categories_[c - 1].id) {
      throw InputError(path, "category id " + std::to_string(categories_[c].id) +
                                 " is listed twice");
    }
  }
}

void DetectionGroundTruth::read_bop_folder(const std::string& path, double min_visible_fraction) {
  format_ = Format::bop;
  source_ = path;
  bop_ = std::make_unique<BopReader>(path);
  std::set<int> object_ids;
  for (std::size_t i = 0; i < bop_->size(); ++i) {
    if (!bop_->has_gt_info(i)) {
      throw InputError(bop_->scene_dir(i) + "/" + bop_layout::kSceneGtInfo,
                       "does not exist; the boxes of a BOP folder come from it (bbox_visib)");
    }
    DetectionImage image;
    image.scene_id = bop_->ref(i).scene_id;
    image.im_id = bop_->ref(i).im_id;
    for (const PartAnnotation& part : bop_->record(i).parts) {
      object_ids.insert(part.obj_id);
      // Parts out of view or hidden behind others have nothing a detector could find.
      if (part.visib_fract <= 0 || part.bbox_visib.empty()) continue;
      TruthBox box;
      box.category_id = part.obj_id;
      box.bbox = {static_cast<double>(part.bbox_visib.x), static_cast<double>(part.bbox_visib.y),
                  static_cast<double>(part.bbox_visib.width),
                  static_cast<double>(part.bbox_visib.height)};
      box.area = box.bbox[2] * box.bbox[3];
      box.crowd = part.visib_fract < min_visible_fraction;
      image.truth.push_back(box);
    }
    images_.push_back(std::move(image));
    reader_index_.push_back(i);
  }
  for (int id : object_ids) categories_.push_back({id, default_category_name(id)});
}

cv::Mat DetectionGroundTruth::load_rgb(std::size_t i) const {
  const std::size_t index = reader_index_.at(i);
  return coco_ ? coco_->load(index).rgb : bop_->load(index).rgb;
}

std::vector<cv::Size> DetectionGroundTruth::check_images(std::size_t loaded_count) const {
  std::vector<cv::Size> sizes;
  for (std::size_t i = 0; i < reader_index_.size(); ++i) {
    const bool loaded = i < loaded_count;
    sizes.push_back(coco_ ? coco_->check_image_size(reader_index_[i], loaded)
                          : bop_->check_boxes_inside_image(reader_index_[i], loaded));
  }
  return sizes;
}

}  // namespace flexsight

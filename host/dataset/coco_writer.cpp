#include "host/dataset/coco_writer.h"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "host/dataset/dataset_files.h"
#include "host/io/input_error.h"
#include "host/io/io_helpers.h"

namespace flexsight {
namespace {

// ordered_json keeps the keys in the order COCO's own files list them.
using OrderedJson = nlohmann::ordered_json;

OrderedJson image_json(const CocoImage& image) {
  OrderedJson entry{{"id", image.id},
                    {"file_name", image.file_name},
                    {"width", image.width},
                    {"height", image.height}};
  if (image.scene_id >= 0) entry["scene_id"] = image.scene_id;
  if (image.im_id >= 0) entry["im_id"] = image.im_id;
  return entry;
}

OrderedJson annotation_json(const CocoAnnotation& annotation, std::int64_t id) {
  const CocoRle& rle = annotation.segmentation;
  return OrderedJson{
      {"id", id},
      {"image_id", annotation.image_id},
      {"category_id", annotation.category_id},
      {"bbox", {annotation.bbox[0], annotation.bbox[1], annotation.bbox[2], annotation.bbox[3]}},
      {"area", annotation.area},
      {"segmentation",
       {{"size", {rle.height, rle.width}}, {"counts", rle_counts_to_string(rle.counts)}}},
      {"iscrowd", annotation.iscrowd}};
}

OrderedJson category_json(const CocoCategory& category) {
  return OrderedJson{
      {"id", category.id}, {"name", category.name}, {"supercategory", category.supercategory}};
}

// "  \"key\": [\n    {...},\n    {...}\n  ]": one entry per line, so the file diffs and
// greps well and stays small.
std::string list_text(const std::string& key, const std::vector<OrderedJson>& entries) {
  std::string text = "  \"" + key + "\": [";
  for (std::size_t i = 0; i < entries.size(); ++i) {
    text += (i == 0 ? "\n    " : ",\n    ") + entries[i].dump();
  }
  return text + (entries.empty() ? "]" : "\n  ]");
}

}  // namespace

std::string default_category_name(int obj_id) {
  char name[32];
  std::snprintf(name, sizeof name, "obj_%02d", obj_id);
  return name;
}

std::vector<CocoAnnotation> coco_annotations_of(const AnnotatedImage& image, std::int64_t image_id,
                                                const std::string& subject) {
  std::vector<CocoAnnotation> annotations;
  for (std::size_t gt_id = 0; gt_id < image.parts.size(); ++gt_id) {
    const PartAnnotation& part = image.parts[gt_id];
    if (part.mask_visib.type() != CV_8UC1 || part.mask_visib.size() != image.rgb.size()) {
      throw InputError(subject,
                       "mask_visib of gt " + std::to_string(gt_id) + " is " +
                           (part.mask_visib.empty() ? std::string("missing")
                                                    : io_detail::describe(part.mask_visib)) +
                           ", expected 8U 1-channel " + io_detail::size_text(image.rgb.size()) +
                           " (the COCO file needs every visible mask)");
    }
    CocoAnnotation annotation;
    annotation.image_id = image_id;
    annotation.category_id = part.obj_id;
    annotation.segmentation = rle_encode(part.mask_visib);
    const std::uint64_t area = rle_area(annotation.segmentation);
    if (area == 0) continue;  // a hidden part: nothing a detector could find
    const cv::Rect box = rle_box(annotation.segmentation);
    annotation.bbox = {double(box.x), double(box.y), double(box.width), double(box.height)};
    annotation.area = static_cast<double>(area);
    annotations.push_back(std::move(annotation));
  }
  return annotations;
}

CocoWriter::CocoWriter(std::string path, std::vector<CocoCategory> categories)
    : path_(std::move(path)), fixed_categories_(!categories.empty()) {
  for (const CocoCategory& category : categories) {
    if (!categories_.emplace(category.id, category).second) {
      throw InputError(path_, "category id " + std::to_string(category.id) + " is listed twice");
    }
  }
}

void CocoWriter::check_categories(const std::vector<CocoAnnotation>& annotations) const {
  if (!fixed_categories_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  for (const CocoAnnotation& annotation : annotations) {
    if (categories_.count(annotation.category_id) == 0) {
      throw InputError(path_, "image " + std::to_string(annotation.image_id) + " has a part of " +
                                  "obj_id " + std::to_string(annotation.category_id) +
                                  ", which is not among the categories");
    }
  }
}

void CocoWriter::add(const CocoImage& image, std::vector<CocoAnnotation> annotations) {
  check_categories(annotations);
  std::lock_guard<std::mutex> lock(mutex_);
  if (images_.count(image.id)) {
    throw InputError(path_, "image id " + std::to_string(image.id) + " is added twice");
  }
  if (!fixed_categories_) {
    for (const CocoAnnotation& annotation : annotations) {
      categories_.emplace(annotation.category_id,
                          CocoCategory{annotation.category_id,
                                       default_category_name(annotation.category_id), "part"});
    }
  }
  images_.emplace(image.id, std::make_pair(image, std::move(annotations)));
}

void CocoWriter::add_category(const CocoCategory& category) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto [found, added] = categories_.emplace(category.id, category);
  if (!added && !(found->second == category)) {
    throw InputError(path_, "category " + std::to_string(category.id) + " is named \"" +
                                found->second.name + "\" and \"" + category.name + "\"");
  }
}

std::string CocoWriter::text() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<OrderedJson> images, annotations, categories;
  std::int64_t next_annotation_id = 1;  // COCOeval takes id 0 for "unmatched"
  for (const auto& [id, entry] : images_) {
    images.push_back(image_json(entry.first));
    for (const CocoAnnotation& annotation : entry.second) {
      annotations.push_back(annotation_json(annotation, next_annotation_id++));
    }
  }
  for (const auto& [id, category] : categories_) categories.push_back(category_json(category));
  return "{\n" + list_text("images", images) + ",\n" + list_text("annotations", annotations) +
         ",\n" + list_text("categories", categories) + "\n}\n";
}

void CocoWriter::finish() const { dataset_files::write_text(path_, text()); }

std::size_t CocoWriter::image_count() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return images_.size();
}

}  // namespace flexsight

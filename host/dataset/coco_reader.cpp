#include "host/dataset/coco_reader.h"

#include <algorithm>
#include <filesystem>
#include <map>

#include "host/dataset/dataset_files.h"
#include "host/dataset/gt_info.h"
#include "host/io/image_header.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/physical_checks.h"

namespace flexsight {
namespace {

using dataset_files::Json;
using dataset_files::require_key;
using dataset_files::to_int;
using dataset_files::to_integer;

const Json& array_at(const Json& root, const std::string& key, const std::string& path) {
  const Json& value = require_key(root, key, path, "top level");
  if (!value.is_array()) {
    throw InputError(path, "\"" + key + "\" must be an array, found " + value.type_name());
  }
  return value;
}

CocoImage image_of(const Json& entry, const std::string& path, const std::string& where) {
  CocoImage image;
  image.id = to_integer(require_key(entry, "id", path, where), path, where + ": id");
  image.file_name = dataset_files::to_string(require_key(entry, "file_name", path, where), path,
                                             where + ": file_name");
  image.width = to_int(require_key(entry, "width", path, where), path, where + ": width");
  image.height = to_int(require_key(entry, "height", path, where), path, where + ": height");
  if (image.width <= 0 || image.height <= 0) {
    throw InputError(path, where + ": width and height must be positive");
  }
  if (entry.contains("scene_id")) image.scene_id = to_int(entry["scene_id"], path, where);
  if (entry.contains("im_id")) image.im_id = to_int(entry["im_id"], path, where);
  return image;
}

CocoRle segmentation_of(const Json& entry, const std::string& path, const std::string& where) {
  const Json& segmentation = require_key(entry, "segmentation", path, where);
  if (segmentation.is_array()) {
    throw InputError(path, where +
                               ": segmentation is a polygon; only RLE segmentations are "
                               "read (docs/dataset.md)");
  }
  const std::string seg_where = where + ": segmentation";
  dataset_files::to_doubles(require_key(segmentation, "size", path, seg_where), 2, path,
                            seg_where + ": size");  // an array of two numbers
  CocoRle rle;
  rle.height = to_int(segmentation["size"][0], path, seg_where + ": size[0]");
  rle.width = to_int(segmentation["size"][1], path, seg_where + ": size[1]");
  const Json& counts = require_key(segmentation, "counts", path, seg_where);
  if (counts.is_string()) {
    rle.counts = rle_counts_from_string(counts.get<std::string>(), path + ": " + seg_where);
  } else if (counts.is_array()) {
    for (std::size_t i = 0; i < counts.size(); ++i) {
      const long long count = to_integer(counts[i], path, seg_where + ": counts");
      if (count < 0 || count > 0xFFFFFFFFLL) {
        throw InputError(path, seg_where + ": count " + std::to_string(count) + " is out of range");
      }
      rle.counts.push_back(static_cast<std::uint32_t>(count));
    }
  } else {
    throw InputError(path, seg_where + ": counts must be a string or a list of integers");
  }
  std::uint64_t total = 0;
  for (std::uint32_t count : rle.counts) total += count;
  if (rle.height < 0 || rle.width < 0 ||
      total != static_cast<std::uint64_t>(rle.height) * rle.width) {
    throw InputError(path, seg_where + ": RLE counts sum to " + std::to_string(total) +
                               ", not size[0] x size[1] = " + std::to_string(rle.height) + " x " +
                               std::to_string(rle.width));
  }
  return rle;
}

CocoAnnotation annotation_of(const Json& entry, const std::string& path, const std::string& where) {
  CocoAnnotation annotation;
  annotation.id = to_integer(require_key(entry, "id", path, where), path, where + ": id");
  annotation.image_id =
      to_integer(require_key(entry, "image_id", path, where), path, where + ": image_id");
  annotation.category_id =
      to_int(require_key(entry, "category_id", path, where), path, where + ": category_id");
  const std::vector<double> bbox =
      dataset_files::to_doubles(require_key(entry, "bbox", path, where), 4, path, where + ": bbox");
  std::copy(bbox.begin(), bbox.end(), annotation.bbox.begin());
  annotation.area =
      dataset_files::to_double(require_key(entry, "area", path, where), path, where + ": area");
  if (entry.contains("iscrowd")) annotation.iscrowd = to_int(entry["iscrowd"], path, where);
  annotation.segmentation = segmentation_of(entry, path, where);
  return annotation;
}

CocoCategory category_of(const Json& entry, const std::string& path, const std::string& where) {
  CocoCategory category;
  category.id = to_int(require_key(entry, "id", path, where), path, where + ": id");
  category.name =
      dataset_files::to_string(require_key(entry, "name", path, where), path, where + ": name");
  category.supercategory =
      entry.contains("supercategory")
          ? dataset_files::to_string(entry["supercategory"], path, where + ": supercategory")
          : std::string();
  return category;
}

// x, y, width, height within the image; a pixel of slack for writers that round.
void require_box_in_image(const std::array<double, 4>& bbox, const CocoImage& image,
                          const std::string& path, const std::string& where) {
  const double slack = 1.0;
  const bool inside = bbox[2] >= 0 && bbox[3] >= 0 && bbox[0] >= -slack && bbox[1] >= -slack &&
                      bbox[0] + bbox[2] <= image.width + slack &&
                      bbox[1] + bbox[3] <= image.height + slack;
  if (!inside) {
    throw InputError(path, where + ": bbox [" + physical_checks::number_text(bbox[0]) + ", " +
                               physical_checks::number_text(bbox[1]) + ", " +
                               physical_checks::number_text(bbox[2]) + ", " +
                               physical_checks::number_text(bbox[3]) +
                               "] is not a box inside the " + std::to_string(image.width) + "x" +
                               std::to_string(image.height) + " image");
  }
}

}  // namespace

CocoDataset read_coco(const std::string& path) {
  const Json root = dataset_files::read_json(path);
  CocoDataset dataset;
  std::map<std::int64_t, const CocoImage*> image_by_id;
  const Json& images = array_at(root, "images", path);
  dataset.images.reserve(images.size());
  for (std::size_t i = 0; i < images.size(); ++i) {
    dataset.images.push_back(image_of(images[i], path, "images[" + std::to_string(i) + "]"));
  }
  for (const CocoImage& image : dataset.images) {
    if (!image_by_id.emplace(image.id, &image).second) {
      throw InputError(path, "image id " + std::to_string(image.id) + " is listed twice");
    }
  }
  if (root.contains("categories")) {
    const Json& categories = array_at(root, "categories", path);
    for (std::size_t i = 0; i < categories.size(); ++i) {
      dataset.categories.push_back(
          category_of(categories[i], path, "categories[" + std::to_string(i) + "]"));
    }
  }
  const Json& annotations = array_at(root, "annotations", path);
  for (std::size_t i = 0; i < annotations.size(); ++i) {
    const std::string where = "annotations[" + std::to_string(i) + "]";
    CocoAnnotation annotation = annotation_of(annotations[i], path, where);
    const auto image = image_by_id.find(annotation.image_id);
    if (image == image_by_id.end()) {
      throw InputError(path, where + ": image_id " + std::to_string(annotation.image_id) +
                                 " is not among the images");
    }
    if (annotation.segmentation.height != image->second->height ||
        annotation.segmentation.width != image->second->width) {
      throw InputError(path, where + ": segmentation size differs from the image's " +
                                 std::to_string(image->second->height) + " x " +
                                 std::to_string(image->second->width));
    }
    require_box_in_image(annotation.bbox, *image->second, path, where);
    const bool known =
        dataset.categories.empty() ||
        std::any_of(dataset.categories.begin(), dataset.categories.end(),
                    [&](const CocoCategory& c) { return c.id == annotation.category_id; });
    if (!known) {
      throw InputError(path, where + ": category_id " + std::to_string(annotation.category_id) +
                                 " is not among the categories");
    }
    dataset.annotations.push_back(std::move(annotation));
  }
  return dataset;
}

CocoReader::CocoReader(std::string path) : path_(std::move(path)), dataset_(read_coco(path_)) {
  std::map<std::int64_t, std::size_t> index_of_id;
  for (std::size_t i = 0; i < dataset_.images.size(); ++i) index_of_id[dataset_.images[i].id] = i;
  annotations_of_image_.resize(dataset_.images.size());
  for (std::size_t a = 0; a < dataset_.annotations.size(); ++a) {
    annotations_of_image_[index_of_id.at(dataset_.annotations[a].image_id)].push_back(a);
  }
}

std::string CocoReader::image_path(std::size_t index) const {
  const std::filesystem::path folder = std::filesystem::path(path_).parent_path();
  return (folder / dataset_.images.at(index).file_name).string();
}

void CocoReader::require_entry_size(std::size_t index, const cv::Size& size) const {
  const CocoImage& entry = dataset_.images.at(index);
  if (size.width == entry.width && size.height == entry.height) return;
  throw InputError(image_path(index), "is " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                                          " but " + path_ + " says " + std::to_string(entry.width) + "x" +
                                          std::to_string(entry.height));
}

cv::Size CocoReader::check_image_size(std::size_t index, bool require_image) const {
  const std::string path = image_path(index);
  if (!require_image && !dataset_files::is_file(path)) return {};
  const cv::Size size = image_size_from_header(path);
  require_entry_size(index, size);
  return size;
}

AnnotatedImage CocoReader::load(std::size_t index) const {
  const CocoImage& entry = dataset_.images.at(index);
  AnnotatedImage image;
  image.scene_id = entry.scene_id >= 0 ? entry.scene_id : 0;
  image.im_id = entry.im_id >= 0 ? entry.im_id : static_cast<int>(entry.id);
  image.rgb = load_rgb8(image_path(index));
  require_entry_size(index, image.rgb.size());
  for (std::size_t a : annotations_of_image_[index]) {
    const CocoAnnotation& annotation = dataset_.annotations[a];
    PartAnnotation part;
    part.obj_id = annotation.category_id;
    part.mask_visib = rle_decode(annotation.segmentation);
    part.bbox_visib = mask_box(part.mask_visib);
    part.px_count_visib = cv::countNonZero(part.mask_visib);
    image.parts.push_back(std::move(part));
  }
  return image;
}

}  // namespace flexsight

#include "host/dataset/dataset_info.h"

#include "host/dataset/bop_layout.h"
#include "host/dataset/dataset_files.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

using dataset_files::Json;
using dataset_files::require_key;

constexpr const char* kFormat = "flexsight-dataset";
constexpr int kFormatVersion = 1;

Json info_json(const DatasetInfo& info) {
  const BopWriterOptions& bop = info.options.bop;
  Json categories = nullptr;  // null: derived from the annotations
  if (!info.options.categories.empty()) {
    categories = Json::array();
    for (const CocoCategory& c : info.options.categories) {
      categories.push_back(
          Json{{"id", c.id}, {"name", c.name}, {"supercategory", c.supercategory}});
    }
  }
  return Json{{"format", kFormat},
              {"format_version", kFormatVersion},
              {"bop",
               {{"rgb_format", bop.rgb_extension()},
                {"jpg_quality", bop.jpg_quality},
                {"depth", bop.write_depth},
                {"masks", bop.write_masks}}},
              {"categories", categories},
              {"coco_file", bop_layout::kCocoFile},
              {"image_count", info.image_count},
              {"settings", info.options.settings}};
}

bool to_bool(const Json& value, const std::string& path, const std::string& where) {
  if (!value.is_boolean()) {
    throw InputError(path, where + ": expected true or false, found " + value.dump());
  }
  return value.get<bool>();
}

}  // namespace

std::string dataset_info_text(const DatasetInfo& info) { return info_json(info).dump(2) + "\n"; }

DatasetInfo read_dataset_info(const std::string& path) {
  const Json root = dataset_files::read_json(path);
  const std::string top = "top level";
  if (!root.is_object() || !root.contains("format") || root["format"] != Json(kFormat)) {
    throw InputError(path, std::string("is not a FlexSight dataset_info.json (no \"format\": \"") +
                               kFormat + "\")");
  }
  const int version =
      dataset_files::to_int(require_key(root, "format_version", path, top), path, "format_version");
  if (version != kFormatVersion) {
    throw InputError(path, "has format_version " + std::to_string(version) + "; this build reads " +
                               std::to_string(kFormatVersion));
  }
  DatasetInfo info;
  const Json& bop = require_key(root, "bop", path, top);
  const std::string rgb = dataset_files::to_string(require_key(bop, "rgb_format", path, "bop"),
                                                   path, "bop: rgb_format");
  if (rgb != "jpg" && rgb != "png") {
    throw InputError(path, "bop: rgb_format \"" + rgb + "\" is neither jpg nor png");
  }
  info.options.bop.rgb_format =
      rgb == "jpg" ? BopWriterOptions::RgbFormat::jpg : BopWriterOptions::RgbFormat::png;
  info.options.bop.jpg_quality =
      dataset_files::to_int(require_key(bop, "jpg_quality", path, "bop"), path, "bop: jpg_quality");
  info.options.bop.write_depth =
      to_bool(require_key(bop, "depth", path, "bop"), path, "bop: depth");
  info.options.bop.write_masks =
      to_bool(require_key(bop, "masks", path, "bop"), path, "bop: masks");
  const Json& categories = require_key(root, "categories", path, top);
  if (!categories.is_null()) {
    if (!categories.is_array()) throw InputError(path, "categories: expected a list or null");
    for (const Json& c : categories) {
      info.options.categories.push_back(CocoCategory{
          dataset_files::to_int(require_key(c, "id", path, "categories"), path, "categories: id"),
          dataset_files::to_string(require_key(c, "name", path, "categories"), path,
                                   "categories: name"),
          dataset_files::to_string(require_key(c, "supercategory", path, "categories"), path,
                                   "categories: supercategory")});
    }
  }
  const std::string coco =
      dataset_files::to_string(require_key(root, "coco_file", path, top), path, "coco_file");
  if (coco != bop_layout::kCocoFile) {
    throw InputError(path,
                     "coco_file is \"" + coco + "\", expected \"" + bop_layout::kCocoFile + "\"");
  }
  info.image_count =
      dataset_files::to_integer(require_key(root, "image_count", path, top), path, "image_count");
  info.options.settings = require_key(root, "settings", path, top);
  return info;
}

std::string dataset_info_difference(const DatasetInfo& a, const DatasetInfo& b) {
  const Json ja = info_json(a), jb = info_json(b);
  for (const auto& [key, value] : ja.items()) {
    if (key != "image_count" && value != jb.at(key)) return key;
  }
  return "";
}

}  // namespace flexsight

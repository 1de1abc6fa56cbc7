#pragma once
// The options of a dataset writer and dataset_info.json, the small file at a dataset's
// root that records them: what a reader needs to know about the files (rgb format, which
// folders exist, the COCO file's name) and what a merge must find equal in every shard.
// It is written last, so its presence marks a finished output.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/dataset/bop_writer.h"
#include "host/dataset/coco_dataset.h"

namespace flexsight {

struct DatasetWriterOptions {
  // The BOP files: rgb format and quality, depth and masks or not.
  BopWriterOptions bop;
  // The COCO categories, fixed (an image with a part of another obj_id is refused), or
  // empty to list the obj_ids that some visible part has, named "obj_NN". A fixed list
  // keeps category ids and names the same across data sets with different parts in view.
  std::vector<CocoCategory> categories;
  // The generator's settings, copied into dataset_info.json as they are ("settings").
  // They must not differ between the shards of one data set (no shard index or seed of
  // a shard here): a merge refuses shards whose settings differ.
  nlohmann::json settings;
};

struct DatasetInfo {
  DatasetWriterOptions options;
  std::int64_t image_count = 0;
};

// The file's text: a JSON object with sorted keys, two-space indents (docs/dataset.md).
std::string dataset_info_text(const DatasetInfo& info);

// Reads and checks dataset_info.json at `path`; InputError naming it when it is not one.
DatasetInfo read_dataset_info(const std::string& path);

// The first key in which `a` and `b` differ, other than image_count ("" when none).
std::string dataset_info_difference(const DatasetInfo& a, const DatasetInfo& b);

}  // namespace flexsight

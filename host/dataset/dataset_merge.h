#pragma once
// Joins the outputs of several DatasetWriters (shards: each a finished output of a
// disjoint set of images, possibly of the same scenes) into one data set whose files
// have the bytes a single DatasetWriter given all the images would have written: the
// scenes' JSON files and the COCO file are written again from their merged content
// (the writers' layout does not depend on the order images came in), the image files
// are copied.
#include <cstdint>
#include <string>
#include <vector>

namespace flexsight {

// Merges `shards` into `out` (created when missing; must be empty). Returns the number
// of images. The shards are left as they are. Throws InputError, before anything is
// written to `out`, naming the file concerned when: a shard has no dataset_info.json
// (unfinished) or one whose options or settings differ from the first shard's; an image
// (scene_id, im_id) or a COCO image id is in two shards; a file the shard's JSON lists
// (rgb, depth, masks) is missing; the shard's COCO file and BOP files list different
// images; or any JSON file is malformed.
std::int64_t merge_datasets(const std::vector<std::string>& shards, const std::string& out);

}  // namespace flexsight

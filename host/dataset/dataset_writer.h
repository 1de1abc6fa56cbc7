#pragma once
// The writer a generator uses: every image into the BOP split folder (bop_writer.h) and
// into the COCO file (coco_writer.h), and at the end dataset_info.json. One output
// folder holds a complete data set or one shard of it (dataset_merge.h joins shards).
//
//   root/000000/rgb/000000.jpg ...     BOP scenes (docs/dataset.md)
//   root/coco_instances.json           COCO instances, file_name relative to root
//   root/dataset_info.json             options, image count, the generator's settings
#include <cstdint>
#include <mutex>
#include <set>
#include <string>

#include "host/dataset/annotated_image.h"
#include "host/dataset/bop_writer.h"
#include "host/dataset/coco_writer.h"
#include "host/dataset/dataset_info.h"

namespace flexsight {

class DatasetWriter {
 public:
  // Writes into `root`, created when missing; throws InputError when it holds anything,
  // or when the options are impossible.
  DatasetWriter(const std::string& root, DatasetWriterOptions options);

  // Writes `image` (BopWriter::write's checks and files) and adds it to the COCO file as
  // image id `image_index`: the image's index in the whole data set, the same whichever
  // shard or thread writes it. Thread-safe, images in any order. Throws InputError for
  // an index or (scene_id, im_id) added before, a part whose mask_visib is missing, or
  // an obj_id not among fixed categories; nothing is written then.
  void add(const AnnotatedImage& image, std::int64_t image_index);

  // Writes the scenes' JSON files, the COCO file and dataset_info.json. Call once, after
  // the last add(); the destructor does not (it must not throw), so an output without
  // dataset_info.json is an unfinished one.
  void finish();

 private:
  std::string root_;
  DatasetWriterOptions options_;
  BopWriter bop_;
  CocoWriter coco_;
  std::mutex mutex_;
  std::set<std::int64_t> indices_;
};

}  // namespace flexsight

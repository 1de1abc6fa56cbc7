#pragma once
// What every synthetic-data generator shares: the run options that say how many images,
// which of them (a shard), where and in which format; and the run that makes them on
// all cores, writes them as a BOP + COCO data set with a contact sheet, shows progress,
// and leaves the output folder whole or untouched.
#include <cstdint>
#include <functional>
#include <string>

#include "host/dataset/annotated_image.h"
#include "host/dataset/dataset_info.h"

namespace flexsight {

struct SynthRunOptions {
  std::string output;       // -o: the data set's folder
  bool overwrite = false;   // --overwrite: replace a non-empty output folder
  std::int64_t count = 0;   // --count: images of the whole data set
  std::uint32_t seed = 1;   // --seed
  int shard_index = 0;      // --shard I/N: this run makes images
  int shard_count = 1;      //   [I * count / N, (I + 1) * count / N)
  int threads = 0;          // --threads: images made at once (0: all cores)
  DatasetWriterOptions dataset;  // --rgb, --no-depth, --no-masks; categories; settings
};

// Images [first, last) of this shard.
std::int64_t shard_first_image(const SynthRunOptions& options);
std::int64_t shard_end_image(const SynthRunOptions& options);

// BOP's placement of image `index` of a data set: scenes of 1000 images (as BOP's
// rendered training sets), scene_id = index / 1000, im_id = index % 1000.
void set_bop_ids(AnnotatedImage& image, std::int64_t index);

// Makes the shard's images with `make_image(index)` (a pure function of the index,
// called from several threads at once), writes them into a staging folder with a
// contact sheet of the first 16, and renames it to options.output when all are
// written. `what` names the images in the progress line ("full-synthetic images").
void run_synthesis(const SynthRunOptions& options,
                   const std::function<AnnotatedImage(std::int64_t index)>& make_image,
                   const std::string& what);

// The contact sheet of the data set in `root` (its first 16 images, read back from
// the files, so a merged data set gets the same picture as a single run's): written to
// root/contact_sheet.png.
void write_dataset_contact_sheet(const std::string& root);

}  // namespace flexsight

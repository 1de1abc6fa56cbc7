#include "host/synth/synth_run.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <filesystem>
#include <mutex>

#include "host/dataset/bop_reader.h"
#include "host/dataset/dataset_writer.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/progress_bar.h"
#include "host/io/staged_folder.h"
#include "host/synth/contact_sheet.h"

namespace flexsight {
namespace {

constexpr int kImagesPerScene = 1000;
constexpr int kContactSheetImages = 16;

}  // namespace

std::int64_t shard_first_image(const SynthRunOptions& options) {
  return options.count * options.shard_index / options.shard_count;
}

std::int64_t shard_end_image(const SynthRunOptions& options) {
  return options.count * (options.shard_index + 1) / options.shard_count;
}

void set_bop_ids(AnnotatedImage& image, std::int64_t index) {
  image.scene_id = static_cast<int>(index / kImagesPerScene);
  image.im_id = static_cast<int>(index % kImagesPerScene);
}

void write_dataset_contact_sheet(const std::string& root) {
  const BopReader reader(root);
  std::vector<AnnotatedImage> images;
  for (std::size_t i = 0; i < std::min<std::size_t>(reader.size(), kContactSheetImages); ++i) {
    images.push_back(reader.load(i));
  }
  if (images.empty()) return;
  write_image(root + "/contact_sheet.png", make_contact_sheet(images));
}

void run_synthesis(const SynthRunOptions& options,
                   const std::function<AnnotatedImage(std::int64_t index)>& make_image,
                   const std::string& what) {
  StagedFolder staged(options.output, options.overwrite);
  DatasetWriter writer(staged.path(), options.dataset);
  const std::int64_t first = shard_first_image(options), end = shard_end_image(options);
  ProgressBar progress(end - first, what);
  // Images are independent; each is made on one thread (small images parallelise far
  // better across images than across the tiles of one). The first error stops the run
  // and is rethrown here; the staging folder is then removed.
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  std::mutex failure_mutex;
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::int64_t index = first; index < end; ++index) {
    if (failed.load()) continue;
    try {
      AnnotatedImage image = make_image(index);
      set_bop_ids(image, index);
      writer.add(image, index);
      progress.advance();
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      failed = true;
    }
  }
  if (failure) std::rethrow_exception(failure);
  writer.finish();
  write_dataset_contact_sheet(staged.path());
  staged.commit();
  progress.finish();
}

}  // namespace flexsight

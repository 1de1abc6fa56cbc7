#include "host/cli/synth_run.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <filesystem>
#include <mutex>

#include "host/cli/arguments.h"
#include "host/cli/progress_bar.h"
#include "host/dataset/bop_reader.h"
#include "host/dataset/dataset_writer.h"
#include "host/io/image_io.h"
#include "host/io/input_error.h"
#include "host/io/staged_folder.h"
#include "host/synth/contact_sheet.h"

namespace flexsight {
namespace {

constexpr int kImagesPerScene = 1000;
constexpr int kContactSheetImages = 16;

}  // namespace

std::string synth_options_help() {
  return "  -o OUT_DIR            the data set's folder (new, or empty)\n"
         "  --count N             images in the whole data set (required)\n"
         "  --seed S              every image is a function of (seed, image index) (default 1)\n"
         "  --shard I/N           make only shard I of N (0 <= I < N): images\n"
         "                        [I*count/N, (I+1)*count/N); join shards with synth merge\n"
         "  --rgb jpg|png         picture format (default jpg, quality 95)\n"
         "  --no-depth            no depth/ images\n"
         "  --no-masks            no mask/ and mask_visib/ images (COCO keeps visible masks)\n"
         "  --threads N           images made at once (default: all cores)\n"
         "  --overwrite           replace OUT_DIR when it is not empty\n";
}

SynthRunOptions take_synth_run_options(std::vector<std::string>& args) {
  SynthRunOptions options;
  options.output = take_option(args, "-o");
  options.overwrite = take_flag(args, "--overwrite");
  const std::string count = take_option(args, "--count");
  const std::string seed = take_option(args, "--seed");
  const std::string shard = take_option(args, "--shard");
  const std::string threads = take_option(args, "--threads");
  const std::string rgb = take_option(args, "--rgb");
  options.dataset.bop.write_depth = !take_flag(args, "--no-depth");
  options.dataset.bop.write_masks = !take_flag(args, "--no-masks");

  if (options.output.empty()) throw InputError("option -o", "an output folder is required");
  if (count.empty()) throw InputError("option --count", "the number of images is required");
  options.count = parse_whole_number("--count", count, 1, std::int64_t(1) << 40);
  if (!seed.empty()) {
    options.seed = static_cast<std::uint32_t>(parse_whole_number("--seed", seed, 0, 4294967295LL));
  }
  if (!threads.empty()) {
    options.threads = static_cast<int>(parse_whole_number("--threads", threads, 0, 4096));
  }
  if (!shard.empty()) {
    const std::size_t slash = shard.find('/');
    if (slash == std::string::npos) {
      throw InputError("option --shard", "expected I/N (e.g. 3/100), got '" + shard + "'");
    }
    options.shard_count =
        static_cast<int>(parse_whole_number("--shard", shard.substr(slash + 1), 1, 1000000));
    options.shard_index = static_cast<int>(
        parse_whole_number("--shard", shard.substr(0, slash), 0, options.shard_count - 1));
    if (options.shard_count > options.count) {
      throw InputError("option --shard", "more shards (" + std::to_string(options.shard_count) +
                                             ") than images (" + std::to_string(options.count) + ")");
    }
  }
  if (rgb == "png") {
    options.dataset.bop.rgb_format = BopWriterOptions::RgbFormat::png;
  } else if (!rgb.empty() && rgb != "jpg") {
    throw InputError("option --rgb", "expected jpg or png, got '" + rgb + "'");
  }
  options.dataset.bop.check();
  return options;
}

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

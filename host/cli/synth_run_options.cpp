#include "host/cli/synth_run_options.h"

#include "host/cli/arguments.h"
#include "host/io/input_error.h"

namespace flexsight {

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

}  // namespace flexsight

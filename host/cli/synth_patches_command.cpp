// flexsight synth patches: segmented patches of parts, cut from any BOP folder with
// mask_visib (the real T-LESS training images, where each part lies alone on black, or
// rendered scenes), for flexsight synth semi.
#include <cstdint>
#include <iostream>

#include "host/cli/arguments.h"
#include "host/cli/synth_commands.h"
#include "host/dataset/bop_reader.h"
#include "host/io/input_error.h"
#include "host/io/progress_bar.h"
#include "host/io/staged_folder.h"
#include "host/synth/patch_cutting.h"

namespace flexsight {
namespace {

void print_help() {
  std::cout << "usage: flexsight synth patches BOP_FOLDER -o PATCHES_DIR [options]\n"
               "  BOP_FOLDER            a BOP scene or split folder with mask_visib/ (e.g. T-LESS\n"
               "                        train_primesense, or a flexsight synth output)\n"
               "  -o PATCHES_DIR        patches as RGBA PNGs in PATCHES_DIR/obj_NNNNNN/ (new, or empty)\n"
               "  --min-visible F       only parts at least this much visible (default 0.95: a\n"
               "                        patch of a hidden part would teach its occluder's look)\n"
               "  --min-pixels N        only parts of at least N visible pixels (default 400)\n"
               "  --overwrite           replace PATCHES_DIR when it is not empty\n";
}

}  // namespace

int run_synth_patches_command(std::vector<std::string> args) {
  if (const auto code = usage_exit_code(args, print_help)) return *code;
  const std::string output = take_option(args, "-o");
  const bool overwrite = take_flag(args, "--overwrite");
  const double min_visible = take_number_option(args, "--min-visible", 0.95);
  const double min_pixels = take_number_option(args, "--min-pixels", 400);
  reject_unknown_options(args);
  if (args.size() != 1) throw InputError("synth patches", "expected one BOP_FOLDER");
  if (!(min_visible >= 0.0 && min_visible <= 1.0)) {
    throw InputError("option --min-visible", "must be in [0, 1]");
  }
  if (!(min_pixels >= 1.0 && min_pixels <= 1e9)) {
    throw InputError("option --min-pixels", "must be a positive number");
  }
  const BopReader reader(args[0]);
  if (reader.size() == 0) throw InputError(args[0], "holds no image");
  StagedFolder staged(output, overwrite);

  ProgressBar progress(static_cast<std::int64_t>(reader.size()), "images");
  const std::int64_t written = cut_patches(reader, args[0], staged.path(), min_visible, min_pixels, progress);
  if (written == 0) {
    throw InputError(args[0], "no part is visible enough for a patch (--min-visible, --min-pixels)");
  }
  staged.commit();
  progress.finish();
  std::cerr << "cut " << written << " patches into " << staged.target() << "\n";
  return 0;
}

}  // namespace flexsight

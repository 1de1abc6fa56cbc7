// flexsight synth merge: the shards of one data set (--shard I/N runs) joined into the
// data set a single run would have written, byte for byte.
#include <iostream>

#include "host/cli/arguments.h"
#include "host/cli/synth_commands.h"
#include "host/dataset/dataset_merge.h"
#include "host/io/input_error.h"
#include "host/io/staged_folder.h"
#include "host/synth/synth_run.h"

namespace flexsight {
namespace {

void print_help() {
  std::cout << "usage: flexsight synth merge SHARD_DIR [SHARD_DIR ...] -o OUT_DIR [--overwrite]\n"
               "  SHARD_DIR   a finished output of flexsight synth ... --shard I/N\n"
               "  -o OUT_DIR  the joined data set (new, or empty)\n"
               "  --overwrite replace OUT_DIR when it is not empty\n"
               "  --partial   join shards that do not make the whole data set\n"
               "The shards must come from the same generator, settings, seed and count; an\n"
               "image in two shards, a missing file or an unfinished shard is refused.\n";
}

}  // namespace

int run_synth_merge_command(std::vector<std::string> args) {
  if (const auto code = usage_exit_code(args, print_help)) return *code;
  const std::string output = take_option(args, "-o");
  const bool overwrite = take_flag(args, "--overwrite");
  const bool partial = take_flag(args, "--partial");
  reject_unknown_options(args);
  if (args.empty()) throw InputError("synth merge", "expected at least one SHARD_DIR");
  StagedFolder staged(output, overwrite);
  const std::int64_t images = merge_datasets(args, staged.path());
  // Shards are joined to make the whole data set; one left out (a failed task of a job
  // array) would otherwise go unnoticed until training on too few images.
  const DatasetInfo info = read_dataset_info(staged.path() + "/dataset_info.json");
  const std::int64_t count = info.options.settings.value("count", std::int64_t(0));
  if (!partial && images != count) {
    throw InputError("synth merge", "the shards hold " + std::to_string(images) + " of the " +
                                        std::to_string(count) +
                                        " images of the data set (a shard is missing?); pass "
                                        "--partial to join them anyway");
  }
  write_dataset_contact_sheet(staged.path());
  staged.commit();
  std::cerr << "merged " << args.size() << " shard(s), " << images << " images, into "
            << staged.target() << "\n";
  return 0;
}

}  // namespace flexsight

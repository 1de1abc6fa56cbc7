// flexsight synth: training and test data for the detector and the pose estimator,
// made from the parts' CAD models (full), from segmented patches of real images
// (semi), the patches themselves (patches), and shards joined (merge).
#include <iostream>

#include "host/cli/commands.h"
#include "host/cli/synth_commands.h"

namespace flexsight {
namespace {

void print_help() {
  std::cout << "usage: flexsight synth <generator> [options]\n"
               "  full     CAD parts rendered over background photographs (full-synthetic)\n"
               "  semi     segmented part patches pasted on background photographs\n"
               "  patches  cut such patches from a BOP folder with mask_visib\n"
               "  merge    join the shards of a data set made with --shard I/N\n"
               "  bin      parts dropped into a bin, seen by the active stereo rig (docs/sim.md)\n"
               "Run 'flexsight synth <generator> --help' for its options; docs/synth.md\n"
               "describes the data sets.\n";
}

}  // namespace

int run_synth_command(std::vector<std::string> args) {
  if (args.empty()) {
    print_help();
    return 1;
  }
  const std::string generator = args.front();
  args.erase(args.begin());
  if (generator == "full") return run_synth_full_command(args);
  if (generator == "semi") return run_synth_semi_command(args);
  if (generator == "patches") return run_synth_patches_command(args);
  if (generator == "merge") return run_synth_merge_command(args);
  if (generator == "bin") return run_synth_bin_command(args);
  if (generator == "--help" || generator == "-h") {
    print_help();
    return 0;
  }
  std::cerr << "flexsight synth: unknown generator '" << generator << "'\n";
  print_help();
  return 1;
}

}  // namespace flexsight

#pragma once
// The generators of `flexsight synth` (host/cli/synth_command.cpp dispatches to them).
#include <string>
#include <vector>

namespace flexsight {

int run_synth_full_command(std::vector<std::string> args);
int run_synth_semi_command(std::vector<std::string> args);
int run_synth_patches_command(std::vector<std::string> args);
int run_synth_merge_command(std::vector<std::string> args);
int run_synth_bin_command(std::vector<std::string> args);

}  // namespace flexsight

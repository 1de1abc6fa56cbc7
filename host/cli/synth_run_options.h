#pragma once
// The options every `flexsight synth` generator shares (host/synth/synth_run.h): how many
// images, which of them (--shard), where and in which format.
#include <string>
#include <vector>

#include "host/synth/synth_run.h"

namespace flexsight {

// Takes SynthRunOptions' options out of `args` (see synth_options_help) and checks them.
// Throws InputError naming the option.
SynthRunOptions take_synth_run_options(std::vector<std::string>& args);
std::string synth_options_help();

}  // namespace flexsight

#pragma once
// pick's and eval-pick's naming options (host/pick/pick_naming.h): --namer, --namer-mix.
#include <string>
#include <vector>

#include "host/pick/pick_session.h"

namespace flexsight {

// Takes --namer MODEL|none and --namer-mix namer|product from `args` into `settings`.
// Without --namer: the shipped namer when it is there (kNamerOnByDefault), else none.
void take_namer_options(std::vector<std::string>& args, PickSettings& settings);

// Their lines of --help.
std::string namer_options_help();

}  // namespace flexsight

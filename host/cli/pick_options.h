#pragma once
// The options `flexsight pick` and `flexsight eval-pick` share: the matcher's (the active
// preset unless another is named), the backend, the detector, templates and CAD folder,
// detection tiles, score and threads.
#include <string>
#include <vector>

#include "host/pick/pick_session.h"

namespace flexsight {

struct PickOptions {
  PickSettings settings;
  bool ndisp_given = false;  // else each pair's calib.txt gives it
};

// Takes the shared options out of `args`; InputError naming the option for a bad or
// missing value (--templates is required).
PickOptions take_pick_options(std::vector<std::string>& args);

// pick's --all and --budget-ms (not eval-pick's: it poses every proposal and times the
// first pick on the way) into `settings.mode`; InputError naming the option for a value
// given to --all, a budget that is not a whole number of milliseconds, or both at once.
void take_pick_mode_options(std::vector<std::string>& args, PickSettings& settings);
std::string pick_mode_options_help();

// The shared options' help lines.
std::string pick_options_help();

// The disparity range of a pair: `options`' --ndisp, else the calib.txt's ndisp
// (InputError naming --ndisp when the calibration has none).
int pick_ndisp(const PickOptions& options, const std::string& calib);

}  // namespace flexsight

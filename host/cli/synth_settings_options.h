#pragma once
// The generators' many numeric settings as command-line options, written once as a
// table (name, field, help) that parses them, prints them with their defaults in
// --help, and records them in dataset_info.json.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/synth/full_synthetic_settings.h"
#include "host/synth/semi_synthetic_settings.h"

namespace flexsight {

struct SettingOption {
  std::string name;        // without the dashes: "min-parts"
  double* real = nullptr;  // exactly one of real / integer is set
  int* integer = nullptr;
  std::string help;
};

// The options of FullSyntheticSettings (names as its check() reports them), pointing
// into `settings`.
std::vector<SettingOption> full_synthetic_setting_options(FullSyntheticSettings& settings);
std::vector<SettingOption> semi_synthetic_setting_options(SemiSyntheticSettings& settings);

// Sets each option given in `args` (removing it); InputError naming the option for a
// malformed value or, for an integer setting, a fraction. Ranges are the settings'
// check()'s job.
void take_settings_options(std::vector<std::string>& args, const std::vector<SettingOption>& options);

// "--size WxH" into width and height when given.
void take_size_option(std::vector<std::string>& args, int& width, int& height);

// One line per option with its current value (the default when nothing was parsed).
std::string settings_options_help(const std::vector<SettingOption>& options);

// Every option's value, and the size, as a JSON object.
nlohmann::json settings_json(const std::vector<SettingOption>& options, int width, int height);

}  // namespace flexsight

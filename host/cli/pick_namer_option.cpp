#include "host/cli/pick_namer_option.h"

#include <filesystem>

#include "host/cli/arguments.h"
#include "host/detect/part_namer.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

// Whether pick names the parts with the shipped namer when no --namer is given
// (docs/detect.md, "Naming the parts", says what it measured).
constexpr bool kNamerOnByDefault = false;

}  // namespace

void take_namer_options(std::vector<std::string>& args, PickSettings& settings) {
  const std::string namer = take_option(args, "--namer");
  const std::string mix = take_option(args, "--namer-mix");
  if (namer == "none") {
    settings.namer.clear();
  } else if (!namer.empty()) {
    if (!std::filesystem::is_regular_file(namer)) throw InputError(namer, "no such file (option --namer)");
    settings.namer = namer;
  } else if (kNamerOnByDefault && std::filesystem::is_regular_file(default_namer_model_path())) {
    settings.namer = default_namer_model_path();
  }
  if (!mix.empty()) settings.naming_mix = parse_naming_mix(mix, "option --namer-mix");
}

std::string namer_options_help() {
  return std::string("  --namer M.onnx|none  name each box with this part namer and pose its best\n"
                     "                     --classes-per-box classes by the namer instead of the\n"
                     "                     detector's (default: ") +
         (kNamerOnByDefault ? default_namer_model_path() + " when present" : std::string("none")) +
         ";\n"
         "                     the shipped one: " +
         default_namer_model_path() +
         ")\n"
         "  --namer-mix product|namer  the classes' order: the namer's probability times\n"
         "                     the detector's score for the class + 0.05 (default), or the\n"
         "                     namer's alone\n";
}

}  // namespace flexsight

#include "host/cli/tile_option.h"

#include "host/cli/arguments.h"
#include <algorithm>

#include "host/detect/tiled_detection.h"
#include "host/io/input_error.h"

namespace flexsight {

int take_tile_option(std::vector<std::string>& args) {
  const std::string text = take_option(args, "--tile");
  if (text.empty() || text == "off") return 0;
  if (text == "auto") {
    throw InputError("option --tile", "auto sizes tiles from measured depth, which only pick has; give N pixels (64..8192) or 0");
  }
  if (text == "0") return 0;
  return static_cast<int>(parse_whole_number("--tile", text, 64, 8192));
}

std::string tile_option_help(int column) {
  const std::string indent(static_cast<std::size_t>(column), ' ');
  const std::string name = "  --tile N";
  return name + std::string(static_cast<std::size_t>(column) - name.size(), ' ') +
         "detect in square tiles of N pixels (64..8192, at most the\n" + indent +
         "image's shorter side) overlapping by a quarter tile, as\n" + indent +
         "pick does; 0 or off: the whole image (default)\n";
}

}  // namespace flexsight

#pragma once
// --tile of detect and eval-det: the detector run on square tiles of N pixels (as pick
// cuts them, host/detect/tiled_detection.h) instead of the whole image. Without the depth
// pick measures there is no part size to size tiles by, so N is given by hand.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "host/detect/tiled_detection.h"  // check_tile_fits, beside the option

namespace flexsight {

// Removes --tile from `args`: 0 or "off" (the whole image, the default) or N in 64..8192.
// "auto" is refused: it needs the measured depth (pick's --tile auto).
int take_tile_option(std::vector<std::string>& args);

// The help lines of --tile (two-column layout starting at `column`).
std::string tile_option_help(int column);

}  // namespace flexsight

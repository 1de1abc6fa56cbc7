#pragma once
// Pictures laid out as a contact sheet: a grid on white, the same for every tool that shows
// many images at once (a data set's annotations, a detector's boxes).
#include <opencv2/core.hpp>
#include <vector>

namespace flexsight {

// What to do with a tile wider than the grid's cell, which resizing to a width may give by
// one column of rounding.
enum class WideTiles {
  kKeep,  // copied whole, into the gap beside its cell
  kTrim,  // cut to the cell's width
};

// RGB (CV_8UC3): `tiles` row-major in a grid of `columns` (fewer when there are fewer
// tiles), cells `tile_width` wide and as tall as the tallest tile, 4 pixels of white around
// each; empty when `tiles` is.
cv::Mat tile_sheet(const std::vector<cv::Mat>& tiles, int tile_width, int columns,
                   WideTiles wide_tiles);

}  // namespace flexsight

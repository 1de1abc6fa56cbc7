#include "host/io/tile_sheet.h"

#include <algorithm>

namespace flexsight {

cv::Mat tile_sheet(const std::vector<cv::Mat>& tiles, int tile_width, int columns_wanted,
                   WideTiles wide_tiles) {
  if (tiles.empty()) return cv::Mat();
  int tile_height = 0;
  for (const cv::Mat& tile : tiles) tile_height = std::max(tile_height, tile.rows);
  constexpr int kGap = 4;
  const int columns = std::min<int>(columns_wanted, static_cast<int>(tiles.size()));
  const int rows = (static_cast<int>(tiles.size()) + columns - 1) / columns;
  cv::Mat sheet(rows * (tile_height + kGap) + kGap, columns * (tile_width + kGap) + kGap,
                CV_8UC3, cv::Scalar(255, 255, 255));
  for (size_t i = 0; i < tiles.size(); ++i) {
    const int column = static_cast<int>(i) % columns, row = static_cast<int>(i) / columns;
    const cv::Mat& tile = tiles[i];
    const int width = wide_tiles == WideTiles::kTrim ? std::min(tile.cols, tile_width) : tile.cols;
    tile(cv::Rect(0, 0, width, tile.rows))
        .copyTo(sheet(cv::Rect(kGap + column * (tile_width + kGap),
                               kGap + row * (tile_height + kGap), width, tile.rows)));
  }
  return sheet;
}

}  // namespace flexsight

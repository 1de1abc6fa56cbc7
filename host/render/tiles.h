#pragma once
// Work over image tiles with OpenMP. Each tile's pixels depend on nothing but their own
// coordinates (and counter-based random keys), so the bytes do not depend on how many
// threads share the tiles or in which order they take them.
#include <omp.h>

#include <algorithm>
#include <opencv2/core.hpp>

namespace flexsight::render_detail {

constexpr int kTileSize = 16;

// Calls body(x0, y0, x1, y1) for every kTileSize square tile of `area` (x1, y1
// exclusive), on `threads` OpenMP threads (0: OpenMP's default). `body` must not throw.
template <class Body>
void for_each_tile(const cv::Rect& area, int threads, const Body& body) {
  if (area.width <= 0 || area.height <= 0) return;
  const int tiles_x = (area.width + kTileSize - 1) / kTileSize;
  const int tiles_y = (area.height + kTileSize - 1) / kTileSize;
  const int tiles = tiles_x * tiles_y;
  const int team = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
  for (int tile = 0; tile < tiles; ++tile) {
    const int x0 = area.x + (tile % tiles_x) * kTileSize;
    const int y0 = area.y + (tile / tiles_x) * kTileSize;
    body(x0, y0, std::min(x0 + kTileSize, area.x + area.width),
         std::min(y0 + kTileSize, area.y + area.height));
  }
}

}  // namespace flexsight::render_detail

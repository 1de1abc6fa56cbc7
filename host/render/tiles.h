#pragma once
// Work over image tiles with OpenMP. Each tile's pixels depend on nothing but their own
// coordinates (and counter-based random keys), so the bytes do not depend on how many
// threads share the tiles or in which order they take them.
#include <omp.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <vector>

namespace flexsight::render_detail {

constexpr int kTileSize = 16;

// Calls body(area, x0, y0, x1, y1) for every kTileSize square tile of every rectangle
// areas[area] (x1, y1 exclusive), all in one OpenMP loop on `threads` threads (0:
// OpenMP's default): one parallel region for many small areas, whose start and end
// would otherwise cost more than their work when the cores are busy. `body` must not
// throw.
template <class Body>
void for_each_tile(const std::vector<cv::Rect>& areas, int threads, const Body& body) {
  struct Tile {
    int area, x0, y0, x1, y1;
  };
  std::vector<Tile> tiles;
  for (int a = 0; a < static_cast<int>(areas.size()); ++a) {
    const cv::Rect& r = areas[a];
    for (int y = r.y; y < r.y + r.height; y += kTileSize) {
      for (int x = r.x; x < r.x + r.width; x += kTileSize) {
        tiles.push_back({a, x, y, std::min(x + kTileSize, r.x + r.width),
                         std::min(y + kTileSize, r.y + r.height)});
      }
    }
  }
  if (tiles.empty()) return;
  const int team = threads > 0 ? threads : omp_get_max_threads();
  const int count = static_cast<int>(tiles.size());
#pragma omp parallel for schedule(dynamic, 1) num_threads(team)
  for (int i = 0; i < count; ++i) {
    const Tile& t = tiles[i];
    body(t.area, t.x0, t.y0, t.x1, t.y1);
  }
}

// The tiles of one rectangle: body(x0, y0, x1, y1).
template <class Body>
void for_each_tile(const cv::Rect& area, int threads, const Body& body) {
  for_each_tile(std::vector<cv::Rect>{area}, threads,
                [&](int, int x0, int y0, int x1, int y1) { body(x0, y0, x1, y1); });
}

}  // namespace flexsight::render_detail

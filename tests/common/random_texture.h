#pragma once
// Synthetic RGB8 images for the tests and the benchmarks: seeded value noise, so every
// run (and every machine) sees the same pixels. Kept apart from test_support.h so that
// code without the test fixtures (the benchmarks) can use it.
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

namespace flexsight::testing_support {

// Random RGB8 texture: value noise on a grid of `cell` pixels, bilinearly interpolated,
// so that it can be sampled at any real x (used to render exact stereo pairs).
class ValueNoiseTexture {
 public:
  ValueNoiseTexture(int width, int height, float cell, unsigned seed)
      : cell_(cell), grid_w_(static_cast<int>(width / cell) + 3),
        grid_h_(static_cast<int>(height / cell) + 3), grid_(3 * grid_w_ * grid_h_) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 255.0f);
    for (float& v : grid_) v = u(rng);
  }
  cv::Vec3b sample(double x, double y) const {
    double gx = x / cell_ + 1.0, gy = y / cell_ + 1.0;
    int x0 = static_cast<int>(std::floor(gx)), y0 = static_cast<int>(std::floor(gy));
    double tx = gx - x0, ty = gy - y0;
    cv::Vec3b out;
    for (int c = 0; c < 3; ++c) {
      double v = (1 - tx) * (1 - ty) * at(x0, y0, c) + tx * (1 - ty) * at(x0 + 1, y0, c) +
                 (1 - tx) * ty * at(x0, y0 + 1, c) + tx * ty * at(x0 + 1, y0 + 1, c);
      out[c] = static_cast<unsigned char>(std::lround(std::min(255.0, std::max(0.0, v))));
    }
    return out;
  }

 private:
  float at(int x, int y, int c) const {
    x = std::min(std::max(x, 0), grid_w_ - 1);
    y = std::min(std::max(y, 0), grid_h_ - 1);
    return grid_[3 * (y * grid_w_ + x) + c];
  }
  float cell_;
  int grid_w_, grid_h_;
  std::vector<float> grid_;
};

// A random RGB8 image (texture cell 2 px).
inline cv::Mat random_rgb8(int width, int height, unsigned seed) {
  ValueNoiseTexture texture(width, height, 2.0f, seed);
  cv::Mat image(height, width, CV_8UC3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at<cv::Vec3b>(y, x) = texture.sample(x, y);
  return image;
}

}  // namespace flexsight::testing_support

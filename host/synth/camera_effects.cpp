#include "host/synth/camera_effects.h"

#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace flexsight {
namespace {

constexpr int kTableBits = 12;
constexpr int kTableSize = 1 << kTableBits;

// The standard normal's quantiles at (i + 0.5) / 4096: a uniform index into this table
// is a Gaussian sample (tails cut at 3.7 sigma, where noise of a few grey levels ends
// anyway). Bisection on erf, once per process.
const std::array<double, kTableSize>& normal_quantiles() {
  static const std::array<double, kTableSize> table = [] {
    std::array<double, kTableSize> q{};
    for (int i = 0; i < kTableSize; ++i) {
      const double p = (i + 0.5) / kTableSize;
      double lo = -10.0, hi = 10.0;
      for (int step = 0; step < 64; ++step) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
      }
      q[i] = 0.5 * (lo + hi);
    }
    return q;
  }();
  return table;
}

std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// cv::RNG's Gaussian fill costs 22 ms at 1280x960; table lookups keyed by a hash of the
// value's index cost a fifth of that: five 12-bit indices per 64-bit hash.
void add_noise(cv::Mat& rgb, double sigma, std::uint64_t key) {
  const auto& quantiles = normal_quantiles();
  std::array<std::int16_t, kTableSize> offsets;
  for (int i = 0; i < kTableSize; ++i) {
    offsets[i] = static_cast<std::int16_t>(std::lround(sigma * quantiles[i]));
  }
  const int values = rgb.cols * rgb.channels();
  for (int y = 0; y < rgb.rows; ++y) {
    std::uint8_t* row = rgb.ptr<std::uint8_t>(y);
    const std::uint64_t row_key = mix64(key + 0x9E3779B97F4A7C15ULL * std::uint64_t(y + 1));
    for (int x = 0; x < values; x += 5) {
      std::uint64_t bits = mix64(row_key + std::uint64_t(x));
      for (int k = x; k < x + 5 && k < values; ++k, bits >>= kTableBits) {
        const int v = row[k] + offsets[bits & (kTableSize - 1)];
        row[k] = static_cast<std::uint8_t>(v < 0 ? 0 : (v > 255 ? 255 : v));
      }
    }
  }
}

}  // namespace

void apply_camera_effects(cv::Mat& rgb, double blur_sigma, double noise_sigma,
                          std::uint64_t noise_key) {
  if (blur_sigma > 0.0) {
    // Kernel of +-3 sigma; OpenCV's 8-bit Gaussian is fixed-point, hence exact bytes.
    cv::GaussianBlur(rgb, rgb, cv::Size(0, 0), blur_sigma, blur_sigma, cv::BORDER_REFLECT_101);
  }
  if (noise_sigma > 0.0) add_noise(rgb, noise_sigma, noise_key);
}

}  // namespace flexsight

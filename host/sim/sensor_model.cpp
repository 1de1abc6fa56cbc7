#include "host/sim/sensor_model.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace flexsight {
namespace {

std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// A standard normal sample from 64 hashed bits: the sum of four 16-bit uniforms
// (Irwin-Hall), scaled to unit variance; tails end at 3.5 sigma, no transcendental
// function, the same bytes everywhere.
float normal_from_bits(std::uint64_t bits) {
  float sum = 0.0f;
  for (int k = 0; k < 4; ++k, bits >>= 16) sum += float(bits & 0xFFFF) * (1.0f / 65536.0f);
  return (sum - 2.0f) * 1.7320508f;
}

}  // namespace

cv::Mat apply_camera_look(const cv::Mat& radiance, const CameraLook& look, std::uint64_t noise_key) {
  cv::Mat out = radiance.clone();
  if (look.defocus_px > 0.0) {
    cv::GaussianBlur(out, out, cv::Size(0, 0), look.defocus_px, look.defocus_px, cv::BORDER_REFLECT_101);
  }
  const double cx = 0.5 * (out.cols - 1), cy = 0.5 * (out.rows - 1);
  const double corner2 = cx * cx + cy * cy;
  const bool sensor = look.full_well_e > 0.0;
  const float to_electrons = float(look.exposure * look.full_well_e);
  const float from_electrons = sensor ? float(look.gain / look.full_well_e) : 1.0f;
  const float read2 = float(look.read_noise_e * look.read_noise_e);
  for (int y = 0; y < out.rows; ++y) {
    cv::Vec3f* row = out.ptr<cv::Vec3f>(y);
    const std::uint64_t row_key = mix64(noise_key + 0x9E3779B97F4A7C15ULL * std::uint64_t(y + 1));
    for (int x = 0; x < out.cols; ++x) {
      const double r2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / corner2;
      const float fall_off = float(1.0 - look.vignetting * r2);
      for (int c = 0; c < 3; ++c) {
        float value = row[x][c] * fall_off;
        if (sensor) {
          const float electrons = std::max(value * to_electrons, 0.0f);
          const float sigma = std::sqrt(electrons + read2);
          value = (electrons + sigma * normal_from_bits(mix64(row_key + std::uint64_t(3 * x + c)))) *
                  from_electrons;
        }
        row[x][c] = value;
      }
    }
  }
  return out;
}

}  // namespace flexsight

#include "host/synth/depth_noise.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "host/io/input_error.h"
#include "host/synth/synth_random.h"

namespace flexsight {

void StereoDepthNoise::check() const {
  if (!(disparity_sigma >= 0.0 && disparity_sigma <= 10.0)) {
    throw InputError("option --depth-noise", "must be in [0, 10] pixels of disparity");
  }
  if (!(baseline_mm > 0.0 && baseline_mm <= 10000.0)) {
    throw InputError("option --depth-baseline", "must be in (0, 10000] mm");
  }
  if (edge_dropout < 0 || edge_dropout > 50) {
    throw InputError("option --depth-dropout", "must be in 0..50 pixels");
  }
}

void apply_stereo_depth_noise(cv::Mat& depth, double focal, const StereoDepthNoise& noise,
                              std::uint64_t key) {
  if (noise.disparity_sigma <= 0.0 || depth.empty()) return;
  // Discontinuities: neighbours whose depths differ by more than 2 % (a step, not a
  // slanted surface), or a surface next to no surface.
  cv::Mat discontinuity(depth.size(), CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < depth.rows; ++y) {
    for (int x = 0; x < depth.cols; ++x) {
      const float z = depth.at<float>(y, x);
      auto step_to = [&](int nx, int ny) {
        if (nx >= depth.cols || ny >= depth.rows) return false;
        const float n = depth.at<float>(ny, nx);
        if ((z > 0.0f) != (n > 0.0f)) return true;
        return z > 0.0f && std::abs(n - z) > 0.02f * std::min(n, z);
      };
      if (step_to(x + 1, y) || step_to(x, y + 1)) discontinuity.at<std::uint8_t>(y, x) = 255;
    }
  }
  if (noise.edge_dropout > 0) {
    const int size = 2 * noise.edge_dropout + 1;
    cv::dilate(discontinuity, discontinuity, cv::getStructuringElement(cv::MORPH_RECT, {size, size}));
  }
  const double fb = focal * noise.baseline_mm;
  for (int y = 0; y < depth.rows; ++y) {
    synth_detail::SynthRandom random(static_cast<std::uint32_t>(key), static_cast<std::int64_t>(key >> 32) * 65536 + y,
                                     synth_detail::kStreamNoise);
    for (int x = 0; x < depth.cols; ++x) {
      // Box-Muller: two uniforms per pixel, whether or not it has depth, so a pixel's
      // noise does not depend on its neighbours.
      const double u1 = 1.0 - random.uniform(), u2 = random.uniform();
      const double gaussian = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
      float& z = depth.at<float>(y, x);
      if (!(z > 0.0f)) continue;
      if (discontinuity.at<std::uint8_t>(y, x)) {
        z = 0.0f;
        continue;
      }
      const double disparity = fb / z + noise.disparity_sigma * gaussian;
      z = disparity > 0.0 ? static_cast<float>(fb / disparity) : 0.0f;
    }
  }
}

}  // namespace flexsight

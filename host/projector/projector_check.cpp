#include "host/projector/projector_check.h"

#include <cmath>
#include <limits>
#include <vector>

#include "host/projector/projector_decode.h"

namespace flexsight {

PixelCheck check_pixel(const cv::Mat& channel, int u, int v, float disparity, const LeftCamera& camera,
                       const ProjectorCalib& projector, const VirtualView& view, const ProjectorCheckParams& params) {
  PixelCheck result;
  const int r = params.window / 2;
  std::vector<float> left;
  left.reserve(std::size_t(params.window * params.window));
  if (!normalised_window(channel, u, v, r, params.min_texture, left)) return result;
  std::vector<int> offsets;  // a fronto-parallel window: two view samples per camera pixel
  for (int dv = -r; dv <= r; ++dv) {
    for (int du = -r; du <= r; ++du) offsets.push_back(2 * du);
  }
  const double tx_over_b = projector.t[0] / camera.baseline_mm;
  const double step = 0.5 / std::abs(tx_over_b);  // px of disparity per view sample
  const double centre_w = u + tx_over_b * (disparity + camera.doffs);
  const int count = int(std::ceil(params.range / step));
  const double sign = tx_over_b > 0 ? 1.0 : -1.0;
  for (int k = -count; k <= count; ++k) {
    const double offset = k * step;  // disparity relative to the stereo's
    const double away = std::abs(offset);
    if (disparity + offset < 0 || (away > 1.0 && away <= 2.0)) continue;
    const int j = view.column(centre_w) + int(sign) * k;
    const double score = window_score(left, view, v, j, r, offsets);
    if (away <= 1.0) {
      result.at_stereo = std::max(result.at_stereo, score);
    } else if (score > result.elsewhere) {
      result.elsewhere = score;
      result.best_disparity = float(disparity + offset);
    }
  }
  result.checked = result.at_stereo > -1.0;
  return result;
}

ProjectorCheckResult check_with_projector(const cv::Mat& left_rgb8, const cv::Mat& disparity,
                                          const MiddleburyCalib& calib, const ProjectorCalib& projector,
                                          const cv::Mat& pattern, const ProjectorCheckParams& params) {
  const LeftCamera camera(calib);
  const VirtualView view = make_virtual_view(camera, projector, pattern);
  const cv::Mat channel = laser_channel(left_rgb8);
  ProjectorCheckResult result;
  result.disparity = disparity.clone();
  result.flagged = cv::Mat(disparity.size(), CV_8UC1, cv::Scalar(0));
  int checked = 0, flagged = 0, replaced = 0;
#pragma omp parallel for schedule(dynamic, 4) reduction(+ : checked, flagged, replaced)
  for (int v = 0; v < disparity.rows; ++v) {
    for (int u = 0; u < disparity.cols; ++u) {
      const float d = disparity.at<float>(v, u);
      if (!std::isfinite(d) || d < 0) continue;
      const PixelCheck pixel = check_pixel(channel, u, v, d, camera, projector, view, params);
      if (!pixel.checked) continue;
      ++checked;
      const bool outscored = pixel.elsewhere - pixel.at_stereo >= params.margin;
      if (!outscored && pixel.at_stereo >= params.floor) continue;
      ++flagged;
      result.flagged.at<std::uint8_t>(v, u) = 255;
      const bool replace = params.replace && outscored && pixel.elsewhere >= params.replace_score;
      result.disparity.at<float>(v, u) = replace ? pixel.best_disparity : std::numeric_limits<float>::infinity();
      replaced += replace;
    }
  }
  result.checked = checked;
  result.flagged_count = flagged;
  result.replaced = replaced;
  return result;
}

}  // namespace flexsight

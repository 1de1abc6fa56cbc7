#include "host/projector/projector_decode.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace flexsight {

cv::Mat laser_channel(const cv::Mat& rgb8) {
  cv::Mat channel(rgb8.size(), CV_32FC1);
  for (int y = 0; y < rgb8.rows; ++y) {
    for (int x = 0; x < rgb8.cols; ++x) {
      const cv::Vec3b& p = rgb8.at<cv::Vec3b>(y, x);  // RGB order (image_io.h)
      channel.at<float>(y, x) = float(p[0]) - 0.5f * (float(p[1]) + float(p[2]));
    }
  }
  return channel;
}

cv::Mat left_right_failures(const cv::Mat& raw_left, const cv::Mat& raw_right, float tolerance) {
  cv::Mat failed(raw_left.size(), CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < raw_left.rows; ++y) {
    for (int x = 0; x < raw_left.cols; ++x) {
      const float d = raw_left.at<float>(y, x);
      bool ok = std::isfinite(d) && d >= 0;
      if (ok) {
        const int xr = int(std::lround(x - d));
        ok = xr >= 0 && xr < raw_right.cols && std::isfinite(raw_right.at<float>(y, xr)) &&
             std::abs(raw_right.at<float>(y, xr) - d) <= tolerance;
      }
      if (!ok) failed.at<std::uint8_t>(y, x) = 255;
    }
  }
  return failed;
}

namespace {

// A window's sample offsets in the virtual view (two samples per camera pixel) for a
// surface whose disparity changes by sx per pixel along the row and sy down the column:
// the projector column of window pixel (du, dv) moves by du - (sx du + sy dv) tx / B.
std::vector<int> window_offsets(int radius, double sx, double sy, double tx_over_b) {
  std::vector<int> offsets;
  for (int dv = -radius; dv <= radius; ++dv) {
    for (int du = -radius; du <= radius; ++du) {
      offsets.push_back(int(std::lround(2.0 * (du + tx_over_b * (sx * du + sy * dv)))));
    }
  }
  return offsets;
}

std::vector<std::vector<int>> slant_offsets(int radius, bool slanted, double tx_over_b) {
  std::vector<std::vector<int>> all{window_offsets(radius, 0, 0, tx_over_b)};
  if (!slanted) return all;
  for (double sx : {0.0, 0.5, 1.0}) {
    for (double sy : {-1.0, 0.0, 1.0}) {
      if (sx != 0 || sy != 0) all.push_back(window_offsets(radius, sx, sy, tx_over_b));
    }
  }
  return all;
}

}  // namespace

bool normalised_window(const cv::Mat& channel, int u, int v, int radius, double min_texture,
                       std::vector<float>& left) {
  left.clear();
  if (u - radius < 0 || v - radius < 0 || u + radius >= channel.cols || v + radius >= channel.rows) return false;
  double mean = 0;
  for (int dv = -radius; dv <= radius; ++dv) {
    for (int du = -radius; du <= radius; ++du) left.push_back(channel.at<float>(v + dv, u + du));
  }
  for (float x : left) mean += x;
  mean /= double(left.size());
  double norm = 0;
  for (float& x : left) {
    x -= float(mean);
    norm += double(x) * x;
  }
  if (std::sqrt(norm / double(left.size())) < min_texture) return false;
  for (float& x : left) x /= float(std::sqrt(norm));
  return true;
}

double window_score(const std::vector<float>& left, const VirtualView& view, int v, int j, int radius,
                    const std::vector<int>& offsets) {
  double sum = 0, sum_sq = 0, cross = 0;
  const int side = 2 * radius + 1;
  for (int k = 0; k < int(offsets.size()); ++k) {
    const int column = j + offsets[std::size_t(k)];
    if (column < 0 || column >= view.samples.cols) return -1.0;
    const double q = view.samples.at<float>(v - radius + k / side, column);
    sum += q;
    sum_sq += q * q;
    cross += left[std::size_t(k)] * q;
  }
  const double n = double(left.size());
  const double var = sum_sq - sum * sum / n;
  if (var <= 1e-12) return -1.0;
  return cross / std::sqrt(var);  // the left window has zero mean and unit norm
}

PixelDecode decode_pixel(const cv::Mat& channel, int u, int v, const LeftCamera& camera,
                         const ProjectorCalib& projector, const VirtualView& view,
                         const ProjectorDecodeParams& params, const StereoVisibility* visibility) {
  PixelDecode result;
  result.disparity = std::numeric_limits<float>::quiet_NaN();
  const int r = params.window / 2;
  std::vector<float> left;
  left.reserve(std::size_t(params.window * params.window));
  if (!normalised_window(channel, u, v, r, params.min_texture, left)) return result;

  // Candidates one view sample apart: a disparity step of B / (2 |tx|).
  const double step = camera.baseline_mm / (2.0 * std::abs(projector.t[0]));
  const int count = int(camera.ndisp / step) + 1;
  const double tx_over_b = projector.t[0] / camera.baseline_mm;
  const std::vector<std::vector<int>> slants = slant_offsets(r, params.slanted, tx_over_b);
  std::vector<double> scores(std::size_t(count), -1.0);
  int best = -1;
  for (int k = 0; k < count; ++k) {
    const double d = k * step;
    if (visibility && !visibility->possible(u, v, d)) continue;
    const int j = view.column(u + tx_over_b * (d + camera.doffs));
    double& score = scores[std::size_t(k)];
    for (const std::vector<int>& offsets : slants) score = std::max(score, window_score(left, view, v, j, r, offsets));
    if (best < 0 || score > scores[std::size_t(best)]) best = k;
  }
  if (best < 0 || scores[std::size_t(best)] <= -1.0) return result;
  result.best = scores[std::size_t(best)];
  for (int k = 0; k < count; ++k) {
    if (std::abs(k - best) > params.peak_halfwidth) result.second = std::max(result.second, scores[std::size_t(k)]);
  }
  double offset = 0;  // parabola through the peak and its neighbours
  if (best > 0 && best + 1 < count) {
    const double a = scores[std::size_t(best - 1)], b = scores[std::size_t(best)], c = scores[std::size_t(best + 1)];
    const double denom = a - 2 * b + c;
    if (denom < 0 && a > -1.0 && c > -1.0) offset = std::clamp(0.5 * (a - c) / denom, -0.5, 0.5);
  }
  result.disparity = float((best + offset) * step);
  return result;
}

ProjectorDecodeResult decode_with_projector(const cv::Mat& left_rgb8, const cv::Mat& disparity,
                                            const cv::Mat& asked, const MiddleburyCalib& calib,
                                            const ProjectorCalib& projector, const cv::Mat& pattern,
                                            const ProjectorDecodeParams& params, const cv::Mat& raw_left,
                                            const cv::Mat& raw_right) {
  const LeftCamera camera(calib);
  const VirtualView view = make_virtual_view(camera, projector, pattern);
  std::unique_ptr<StereoVisibility> visibility;
  if (params.visibility) {
    visibility = std::make_unique<StereoVisibility>(raw_left, raw_right, camera, projector, view,
                                                    params.visibility_tolerance);
  }
  const cv::Mat channel = laser_channel(left_rgb8);
  ProjectorDecodeResult result;
  result.disparity = disparity.clone();
  result.state = cv::Mat(disparity.size(), CV_8UC1, cv::Scalar(0));
  int asked_count = 0, decoded_count = 0;
#pragma omp parallel for schedule(dynamic, 4) reduction(+ : asked_count, decoded_count)
  for (int v = 0; v < disparity.rows; ++v) {
    for (int u = 0; u < disparity.cols; ++u) {
      if (asked.at<std::uint8_t>(v, u) == 0) continue;
      ++asked_count;
      const PixelDecode pixel = decode_pixel(channel, u, v, camera, projector, view, params, visibility.get());
      if (pixel.distinct(params)) {
        result.disparity.at<float>(v, u) = pixel.disparity;
        result.state.at<std::uint8_t>(v, u) = 1;
        ++decoded_count;
      } else {
        result.state.at<std::uint8_t>(v, u) = 2;
      }
    }
  }
  result.asked = asked_count;
  result.decoded = decoded_count;
  return result;
}

}  // namespace flexsight

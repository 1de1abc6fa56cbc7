#include "host/projector/projector_calibrate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "host/projector/projector_decode.h"

namespace flexsight {

ProjectorCalib projector_on_baseline(const MiddleburyCalib& calib, double fov_degrees, double offset_x_mm,
                                     const std::string& pattern) {
  ProjectorCalib projector;
  const double f = calib.cam0[0];
  const int size = 2 * int(std::ceil(f * std::tan(fov_degrees * M_PI / 360.0))) + 1;
  const double centre = (size - 1) / 2.0;
  projector.K = {f, 0, centre, 0, f, centre, 0, 0, 1};
  projector.width = projector.height = size;
  projector.t = {0.0 - (calib.baseline_mm / 2.0 + offset_x_mm), 0.0, 0.0};
  projector.pattern = pattern;
  return projector;
}

namespace {
constexpr int kNormWindow = 15;  // px: the local mean and spread of the laser channel
}

CalibrationView calibration_view(const cv::Mat& left_rgb8, const cv::Mat& disparity, const cv::Mat& confident,
                                 const MiddleburyCalib& calib) {
  CalibrationView view;
  view.calib = calib;
  const cv::Mat channel = laser_channel(left_rgb8);
  cv::Mat mean, mean_sq;
  cv::boxFilter(channel, mean, CV_32F, cv::Size(kNormWindow, kNormWindow));
  cv::boxFilter(channel.mul(channel), mean_sq, CV_32F, cv::Size(kNormWindow, kNormWindow));
  cv::Mat spread;
  cv::sqrt(cv::max(mean_sq - mean.mul(mean), 1.0f), spread);
  view.normalised = (channel - mean) / spread;
  view.disparity = cv::Mat(disparity.size(), CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  disparity.copyTo(view.disparity, confident);
  return view;
}

cv::Mat PatternEstimate::image8() const {
  cv::Mat image;
  mean.convertTo(image, CV_8U, 255.0 / 4.0, 255.0 / 4.0);
  return image;
}

PatternEstimate estimate_pattern(const std::vector<CalibrationView>& views, const ProjectorCalib& projector,
                                 float min_disparity, float max_disparity) {
  cv::Mat sum(projector.height, projector.width, CV_64FC1, cv::Scalar(0));
  cv::Mat weight(projector.height, projector.width, CV_64FC1, cv::Scalar(0));
  for (const CalibrationView& view : views) {
    const LeftCamera camera(view.calib);
    for (int v = 0; v < view.disparity.rows; ++v) {
      for (int u = 0; u < view.disparity.cols; ++u) {
        const float d = view.disparity.at<float>(v, u);
        if (!std::isfinite(d) || d < min_disparity || d >= max_disparity) continue;
        const Eigen::Vector2d p = project_to_pattern(projector, camera.point(u, v, d));
        if (!std::isfinite(p.x())) continue;
        const int x0 = int(std::floor(p.x())), y0 = int(std::floor(p.y()));
        if (x0 < 0 || y0 < 0 || x0 + 1 >= projector.width || y0 + 1 >= projector.height) continue;
        const double fx = p.x() - x0, fy = p.y() - y0, value = view.normalised.at<float>(v, u);
        const double w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
        const int xs[4] = {x0, x0 + 1, x0, x0 + 1}, ys[4] = {y0, y0, y0 + 1, y0 + 1};
        for (int k = 0; k < 4; ++k) {
          sum.at<double>(ys[k], xs[k]) += w[k] * value;
          weight.at<double>(ys[k], xs[k]) += w[k];
        }
      }
    }
  }
  PatternEstimate estimate;
  cv::Mat mean = sum / cv::max(weight, 1e-9);
  mean.setTo(0, weight < 1e-9);
  mean.convertTo(estimate.mean, CV_32F);
  weight.convertTo(estimate.weight, CV_32F);
  return estimate;
}

double pattern_coverage(const PatternEstimate& estimate, const MiddleburyCalib& calib,
                        const ProjectorCalib& projector, double min_weight) {
  const LeftCamera camera(calib);
  const cv::Mat inside(estimate.weight.size(), CV_32FC1, cv::Scalar(1));
  const VirtualView reach = make_virtual_view(camera, projector, inside);
  const VirtualView covered = make_virtual_view(camera, projector, estimate.weight);
  const cv::Mat reachable = reach.samples > 0.999f;
  const int needed = cv::countNonZero(reachable);
  const int have = cv::countNonZero(reachable & (covered.samples >= float(min_weight)));
  return needed ? double(have) / needed : 0.0;
}

double pattern_agreement(const cv::Mat& a, const cv::Mat& a_weight, const cv::Mat& b, const cv::Mat& b_weight,
                         double min_weight) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
  for (int y = 0; y < a.rows; ++y) {
    for (int x = 0; x < a.cols; ++x) {
      if (a_weight.at<float>(y, x) < min_weight || b_weight.at<float>(y, x) < min_weight) continue;
      const double p = a.at<float>(y, x), q = b.at<float>(y, x);
      sa += p, sb += q, saa += p * p, sbb += q * q, sab += p * q, n += 1;
    }
  }
  if (n < 2) return 0.0;
  const double var_a = saa - sa * sa / n, var_b = sbb - sb * sb / n;
  if (var_a <= 0 || var_b <= 0) return 0.0;
  return (sab - sa * sb / n) / std::sqrt(var_a * var_b);
}

double split_agreement(const std::vector<CalibrationView>& views, const ProjectorCalib& projector) {
  std::vector<CalibrationView> even, odd;
  for (std::size_t i = 0; i < views.size(); ++i) (i % 2 == 0 ? even : odd).push_back(views[i]);
  if (even.empty() || odd.empty()) return 0.0;
  const PatternEstimate a = estimate_pattern(even, projector), b = estimate_pattern(odd, projector);
  return pattern_agreement(a.mean, a.weight, b.mean, b.weight);
}

}  // namespace flexsight

#include "host/projector/projector_view.h"

#include <cmath>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "host/io/input_error.h"

namespace flexsight {

LeftCamera::LeftCamera(const MiddleburyCalib& calib)
    : f(calib.cam0[0]), cx(calib.cam0[2]), cy(calib.cam0[5]), baseline_mm(calib.baseline_mm),
      doffs(calib.doffs), width(calib.width), height(calib.height), ndisp(calib.ndisp) {}

Eigen::Vector3d LeftCamera::point(double u, double v, double d) const {
  const double z = f * baseline_mm / (d + doffs);
  return {(u - cx) * z / f, (v - cy) * z / f, z};
}

Eigen::Vector2d project_to_pattern(const ProjectorCalib& p, const Eigen::Vector3d& x) {
  const Eigen::Matrix3d R = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(p.R.data());
  const Eigen::Vector3d q = R * x + Eigen::Vector3d(p.t[0], p.t[1], p.t[2]);
  if (!(q.z() > 0)) return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  return {p.K[0] * q.x() / q.z() + p.K[2], p.K[4] * q.y() / q.z() + p.K[5]};
}

cv::Mat load_pattern(const ProjectorCalib& projector) {
  const cv::Mat raw = cv::imread(projector.pattern_path, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
  if (raw.empty()) throw InputError(projector.pattern_path, "cannot be read as an image");
  if (raw.cols != projector.width || raw.rows != projector.height) {
    throw InputError(projector.pattern_path, "is not projwidth x projheight");
  }
  cv::Mat pattern;
  raw.convertTo(pattern, CV_32F, raw.depth() == CV_16U ? 1.0 / 65535.0 : 1.0 / 255.0);
  return pattern;
}

void require_rectified_projector(const ProjectorCalib& p, const std::string& source) {
  constexpr double kTolerance = 1e-6;
  for (int i = 0; i < 9; ++i) {
    if (std::abs(p.R[i] - (i % 4 == 0 ? 1.0 : 0.0)) > kTolerance) {
      throw InputError(source, "projR must be the identity: the decoder needs the projector rectified with the cameras");
    }
  }
  if (std::abs(p.t[1]) > kTolerance || std::abs(p.t[2]) > kTolerance) {
    throw InputError(source, "projt must lie along the baseline ([tx 0 0]) for the decoder");
  }
  if (std::abs(p.t[0]) < 1.0) throw InputError(source, "projt's tx must be at least 1 mm: a projector at the left camera gives no depth");
}

VirtualView make_virtual_view(const LeftCamera& camera, const ProjectorCalib& p, const cv::Mat& pattern) {
  const double tx = p.t[0];
  const double w_a = tx * camera.doffs / camera.baseline_mm;
  const double w_b = tx * (camera.doffs + camera.ndisp) / camera.baseline_mm;
  VirtualView view;
  view.w0 = std::floor(std::min(w_a, w_b)) - 16.0;  // margin for windows
  const double w_end = camera.width + std::ceil(std::max(w_a, w_b)) + 16.0;
  const int columns = int(2.0 * (w_end - view.w0)) + 1;
  cv::Mat map_x(camera.height, columns, CV_32FC1), map_y(camera.height, columns, CV_32FC1);
  for (int v = 0; v < camera.height; ++v) {
    const float vp = float(p.K[4] / camera.f * (v - camera.cy) + p.K[5]);
    for (int j = 0; j < columns; ++j) {
      const double w = view.w0 + 0.5 * j;
      map_x.at<float>(v, j) = float(p.K[0] / camera.f * (w - camera.cx) + p.K[2]);
      map_y.at<float>(v, j) = vp;
    }
  }
  cv::remap(pattern, view.samples, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
  return view;
}

}  // namespace flexsight

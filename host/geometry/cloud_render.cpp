#include "host/geometry/cloud_render.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace flexsight {
namespace {

// Median of each coordinate: a centre that stray far points do not drag away.
Eigen::Vector3f median_point(const std::vector<Eigen::Vector3f>& points) {
  Eigen::Vector3f centre;
  std::vector<float> values(points.size());
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < points.size(); ++i) values[i] = points[i][k];
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    centre[k] = values[values.size() / 2];
  }
  return centre;
}

// The 2nd and 98th percentiles of `values`: a frame that stray points do not widen.
std::pair<float, float> robust_range(std::vector<float> values) {
  const size_t low = values.size() / 50, high = values.size() - 1 - values.size() / 50;
  std::nth_element(values.begin(), values.begin() + low, values.end());
  const float a = values[low];
  std::nth_element(values.begin(), values.begin() + high, values.end());
  return {a, values[high]};
}

}  // namespace

cv::Mat render_point_cloud(const PointCloud& cloud, const CloudView& view) {
  cv::Mat image(view.height, view.width, CV_8UC3, cv::Scalar(24, 24, 32));
  if (cloud.size() == 0) return image;
  const Eigen::Vector3f centre = median_point(cloud.points);
  const float distance = centre.norm();
  const float yaw = static_cast<float>(view.yaw_degrees * M_PI / 180.0);
  const float pitch = static_cast<float>(view.pitch_degrees * M_PI / 180.0);
  const Eigen::Matrix3f rotation =
      (Eigen::AngleAxisf(pitch, Eigen::Vector3f::UnitX()) *
       Eigen::AngleAxisf(yaw, Eigen::Vector3f::UnitY()))
          .toRotationMatrix();
  // Virtual camera: orbit the centre at the same distance, looking at it.
  std::vector<Eigen::Vector3f> camera_points(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i) {
    camera_points[i] = rotation * (cloud.points[i] - centre) + Eigen::Vector3f(0, 0, distance);
  }
  // Frame the cloud: its normalised image coordinates' robust range fills 90 % of the
  // picture, centred.
  std::vector<float> us, vs;
  for (const Eigen::Vector3f& p : camera_points) {
    if (p.z() <= 0) continue;
    us.push_back(p.x() / p.z());
    vs.push_back(p.y() / p.z());
  }
  if (us.empty()) return image;
  const auto [u_low, u_high] = robust_range(us);
  const auto [v_low, v_high] = robust_range(vs);
  const float focal = 0.9f * std::min(view.width / std::max(u_high - u_low, 1e-6f),
                                      view.height / std::max(v_high - v_low, 1e-6f));
  const float cx = 0.5f * view.width - focal * 0.5f * (u_low + u_high);
  const float cy = 0.5f * view.height - focal * 0.5f * (v_low + v_high);
  // Splat radius: about the spacing of the original pixels on the new image.
  const int radius = std::clamp(
      static_cast<int>(std::lround(std::sqrt(static_cast<double>(view.width) * view.height /
                                             static_cast<double>(cloud.size())) * 0.7)),
      0, 3);
  const Eigen::Vector3f light = Eigen::Vector3f(0.3f, -0.5f, -1.0f).normalized();

  std::vector<float> depth(static_cast<size_t>(view.width) * view.height,
                           std::numeric_limits<float>::infinity());
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& p = camera_points[i];
    if (p.z() <= 0) continue;
    const int u = static_cast<int>(std::lround(cx + focal * p.x() / p.z()));
    const int v = static_cast<int>(std::lround(cy + focal * p.y() / p.z()));
    const Eigen::Vector3f normal = rotation * cloud.normals[i];
    const float lit = std::abs(normal.dot(light));
    const float gain = static_cast<float>(1.0 - view.shading + view.shading * lit);
    const cv::Vec3b& c = cloud.colors[i];
    const cv::Vec3b shaded(cv::saturate_cast<uchar>(c[0] * gain),
                           cv::saturate_cast<uchar>(c[1] * gain),
                           cv::saturate_cast<uchar>(c[2] * gain));
    for (int dv = -radius; dv <= radius; ++dv) {
      for (int du = -radius; du <= radius; ++du) {
        const int x = u + du, y = v + dv;
        if (x < 0 || y < 0 || x >= view.width || y >= view.height) continue;
        float& nearest = depth[static_cast<size_t>(y) * view.width + x];
        if (p.z() >= nearest) continue;
        nearest = p.z();
        image.at<cv::Vec3b>(y, x) = shaded;
      }
    }
  }
  return image;
}

}  // namespace flexsight

#include "host/sim/dot_projector.h"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "host/io/input_error.h"
#include "host/synth/synth_random.h"

namespace flexsight {
namespace {

constexpr double kDegrees = M_PI / 180.0;
// Spots are summed out to this many sigmas (exp(-4.5) = 1 %).
constexpr double kReach = 3.0;
// Below this pattern value a pixel gets no shadow ray (and no light).
constexpr double kDarkEnough = 1e-4;

}  // namespace

void ProjectorSettings::check() const {
  if (dots < 1 || dots > 10000000) {
    throw InputError("option --dots", "expected 1..10000000 dots, got " + std::to_string(dots));
  }
  if (!(fov_degrees > 0.0 && fov_degrees < 170.0)) {
    throw InputError("option --projector-fov",
                     "expected a field of view in (0, 170) degrees, got " + std::to_string(fov_degrees));
  }
  if (!(dot_sigma_degrees > 0.0 && dot_sigma_degrees <= 5.0)) {
    throw InputError("option --dot-size",
                     "expected a dot radius in (0, 5] degrees, got " + std::to_string(dot_sigma_degrees));
  }
  if (!(power >= 0.0f && std::isfinite(power))) {
    throw InputError("option --projector-power", "must be a finite number >= 0");
  }
}

DotPattern::DotPattern(const ProjectorSettings& settings) : settings_(settings) {
  settings_.check();
  half_field_ = 0.5 * settings_.fov_degrees * kDegrees;
  synth_detail::SynthRandom random(settings_.pattern_seed, 0, 0x9A77E2);
  dots_.reserve(settings_.dots);
  for (int i = 0; i < settings_.dots; ++i) {
    const double a = random.uniform(-half_field_, half_field_);
    const double b = random.uniform(-half_field_, half_field_);
    dots_.emplace_back(a, b);
  }
  // About four dots per cell.
  cells_ = std::max(1, int(std::sqrt(settings_.dots / 4.0)));
  cell_ = 2.0 * half_field_ / cells_;
  grid_.resize(std::size_t(cells_) * cells_);
  for (int i = 0; i < int(dots_.size()); ++i) {
    const int cx = std::min(cells_ - 1, int((dots_[i].x() + half_field_) / cell_));
    const int cy = std::min(cells_ - 1, int((dots_[i].y() + half_field_) / cell_));
    grid_[std::size_t(cy) * cells_ + cx].push_back(i);
  }
}

double DotPattern::intensity(const Eigen::Vector2d& a, double extra_sigma) const {
  const double sigma = settings_.dot_sigma_degrees * kDegrees;
  const double variance = sigma * sigma + extra_sigma * extra_sigma;
  const double reach = kReach * std::sqrt(variance);
  if (std::abs(a.x()) > half_field_ + reach || std::abs(a.y()) > half_field_ + reach) return 0.0;
  const int x0 = std::max(0, int(std::floor((a.x() - reach + half_field_) / cell_)));
  const int x1 = std::min(cells_ - 1, int(std::floor((a.x() + reach + half_field_) / cell_)));
  const int y0 = std::max(0, int(std::floor((a.y() - reach + half_field_) / cell_)));
  const int y1 = std::min(cells_ - 1, int(std::floor((a.y() + reach + half_field_) / cell_)));
  double sum = 0.0;
  for (int cy = y0; cy <= y1; ++cy) {
    for (int cx = x0; cx <= x1; ++cx) {
      for (int i : grid_[std::size_t(cy) * cells_ + cx]) {
        const double d2 = (dots_[i] - a).squaredNorm();
        if (d2 < reach * reach) sum += std::exp(-0.5 * d2 / variance);
      }
    }
  }
  return sum * (sigma * sigma / variance);
}

cv::Mat projector_radiance(const RenderScene& scene, const RaycastImages& images,
                           const PinholeCamera& camera, const Eigen::Vector3d& projector,
                           const DotPattern& pattern, int threads) {
  const ProjectorSettings& settings = pattern.settings();
  cv::Mat radiance = cv::Mat::zeros(images.depth.size(), CV_32FC3);
  const RTCScene embree = scene.embree_scene();
  const int rows = images.depth.rows, cols = images.depth.cols;
  const int thread_count = threads > 0 ? threads : omp_get_max_threads();
  const double blur = settings.blur_sigma_degrees * kDegrees;
  // Rows are independent: any split gives the same bytes.
#pragma omp parallel for schedule(dynamic, 8) num_threads(thread_count)
  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < cols; ++x) {
      const int instance = images.instance.at<int>(y, x);
      if (instance < 0) continue;
      const cv::Vec3f& p = images.point.at<cv::Vec3f>(y, x);
      const Eigen::Vector3d point(p[0], p[1], p[2]);
      const Eigen::Vector3d q = point - projector;  // projector -> surface
      if (q.z() <= 0.0) continue;
      const cv::Vec3f& n = images.normal.at<cv::Vec3f>(y, x);
      const double distance = q.norm();
      const double cosine = -Eigen::Vector3d(n[0], n[1], n[2]).dot(q) / distance;
      if (cosine <= 0.0) continue;
      // The pixel's width on a surface facing the camera, as an angle at the projector.
      const double footprint = point.z() / camera.fx / distance;
      const double extra = blur > 0.0 ? std::sqrt(footprint * footprint / 12.0 + blur * blur)
                                      : footprint / std::sqrt(12.0);
      const double value = pattern.intensity(
          Eigen::Vector2d(std::atan(q.x() / q.z()), std::atan(q.y() / q.z())), extra);
      if (value < kDarkEnough) continue;
      // Shadow ray from the surface (moved off it along the geometric normal) to the
      // projector.
      const cv::Vec3f& g = images.geometric_normal.at<cv::Vec3f>(y, x);
      const float offset = 1e-5f * std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])}) + 1e-4f;
      RTCRay ray;
      ray.org_x = p[0] + offset * g[0];
      ray.org_y = p[1] + offset * g[1];
      ray.org_z = p[2] + offset * g[2];
      ray.dir_x = float(projector.x()) - ray.org_x;
      ray.dir_y = float(projector.y()) - ray.org_y;
      ray.dir_z = float(projector.z()) - ray.org_z;
      ray.tnear = 0.0f;
      ray.tfar = 1.0f - 1e-4f;
      ray.time = 0.0f;
      ray.mask = 0xFFFFFFFF;
      ray.id = 0;
      ray.flags = 0;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      rtcOccluded1(embree, &context, &ray);
      if (ray.tfar < 0.0f) continue;  // blocked: Embree sets tfar to -inf
      const Eigen::Vector3f& albedo = scene.instance(instance).material.albedo;
      const float scale = settings.power * float(cosine * value);
      radiance.at<cv::Vec3f>(y, x) = {scale * settings.colour.x() * albedo.x(),
                                      scale * settings.colour.y() * albedo.y(),
                                      scale * settings.colour.z() * albedo.z()};
    }
  }
  return radiance;
}

}  // namespace flexsight

#pragma once
// Stereo pairs ray-traced from known geometry and a known rectified rig: a slanted
// textured plane, optionally with a sphere in front. The tests of the 3D output compare
// the point cloud from such a pair with the surface it was rendered from.
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <optional>

#include "host/geometry/stereo_camera.h"
#include "tests/common/random_texture.h"

namespace flexsight::testing_support {

struct SyntheticRig {
  int width = 192;
  int height = 144;
  double focal = 220;  // px
  double cx = 95.5;
  double cy = 71.5;
  double baseline = 60;  // mm; the right camera sits at (baseline, 0, 0)

  StereoCamera camera() const {
    StereoCamera rig;
    rig.Q = reprojection_matrix(focal, cx, cy, cx, baseline);
    rig.width = width;
    rig.height = height;
    return rig;
  }
  Eigen::Vector3d ray(double x, double y) const {
    return Eigen::Vector3d((x - cx) / focal, (y - cy) / focal, 1.0);
  }
};

struct Plane3 {
  Eigen::Vector3d normal;  // unit
  double offset;           // normal . P = offset
};

struct Sphere3 {
  Eigen::Vector3d centre;
  double radius;
};

// The nearest surface hit along origin + t * direction: its t and unit normal.
struct Hit {
  double t = std::numeric_limits<double>::infinity();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  bool on_sphere = false;
};

class SyntheticScene {
 public:
  SyntheticScene(Plane3 plane, std::optional<Sphere3> sphere) : plane_(plane), sphere_(sphere) {}

  Hit trace(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const {
    Hit hit;
    const double facing = plane_.normal.dot(direction);
    if (std::abs(facing) > 1e-12) {
      const double t = (plane_.offset - plane_.normal.dot(origin)) / facing;
      if (t > 0) hit = {t, plane_.normal, false};
    }
    if (sphere_) {
      const Eigen::Vector3d oc = origin - sphere_->centre;
      const double a = direction.squaredNorm();
      const double b = 2 * oc.dot(direction);
      const double c = oc.squaredNorm() - sphere_->radius * sphere_->radius;
      const double disc = b * b - 4 * a * c;
      if (disc >= 0) {
        const double t = (-b - std::sqrt(disc)) / (2 * a);
        if (t > 0 && t < hit.t) {
          hit = {t, (origin + t * direction - sphere_->centre).normalized(), true};
        }
      }
    }
    if (hit.normal.dot(direction) > 0) hit.normal = -hit.normal;  // face the viewer
    return hit;
  }

  // The left-view surface point of pixel (x, y).
  Hit trace_left(const SyntheticRig& rig, double x, double y) const {
    return trace(Eigen::Vector3d::Zero(), rig.ray(x, y));
  }

 private:
  Plane3 plane_;
  std::optional<Sphere3> sphere_;
};

struct RenderedScene {
  cv::Mat left, right;  // CV_8UC3 RGB
  cv::Mat disparity;    // CV_32FC1, true left-view disparity at pixel centres
  cv::Mat visible;      // CV_8UC1, 255 where the left pixel's point is seen by the right camera
};

// Renders with 3x3 supersampling. The texture is attached to the surfaces (a solid
// texture of the 3D point), so the two views see the same surface pattern.
inline RenderedScene render_scene(const SyntheticRig& rig, const SyntheticScene& scene) {
  const ValueNoiseTexture texture(1200, 1200, 2.0f, 5);
  const double mm_per_texel = 3.0;
  auto shade = [&](const Eigen::Vector3d& origin, double x, double y) {
    cv::Vec3d sum(0, 0, 0);
    for (int sy = -1; sy <= 1; ++sy) {
      for (int sx = -1; sx <= 1; ++sx) {
        const Eigen::Vector3d direction = rig.ray(x + sx / 3.0, y + sy / 3.0);
        const Hit hit = scene.trace(origin, direction);
        const Eigen::Vector3d p = origin + hit.t * direction;
        const cv::Vec3b c = texture.sample(600 + (p.x() + 0.6 * p.z()) / mm_per_texel,
                                           600 + (p.y() + 0.3 * p.z()) / mm_per_texel);
        sum += cv::Vec3d(c[0], c[1], c[2]);
      }
    }
    return cv::Vec3b(cv::saturate_cast<uchar>(sum[0] / 9), cv::saturate_cast<uchar>(sum[1] / 9),
                     cv::saturate_cast<uchar>(sum[2] / 9));
  };
  RenderedScene out{cv::Mat(rig.height, rig.width, CV_8UC3),
                    cv::Mat(rig.height, rig.width, CV_8UC3),
                    cv::Mat(rig.height, rig.width, CV_32FC1),
                    cv::Mat(rig.height, rig.width, CV_8UC1)};
  const Eigen::Vector3d right_centre(rig.baseline, 0, 0);
  for (int y = 0; y < rig.height; ++y) {
    for (int x = 0; x < rig.width; ++x) {
      out.left.at<cv::Vec3b>(y, x) = shade(Eigen::Vector3d::Zero(), x, y);
      out.right.at<cv::Vec3b>(y, x) = shade(right_centre, x, y);
      const Hit hit = scene.trace_left(rig, x, y);
      const Eigen::Vector3d p = hit.t * rig.ray(x, y);
      const double d = rig.focal * rig.baseline / p.z();
      out.disparity.at<float>(y, x) = static_cast<float>(d);
      // Seen from the right camera when nothing is nearer along that ray.
      const Eigen::Vector3d to_point = p - right_centre;
      const Hit from_right = scene.trace(right_centre, to_point.normalized());
      const bool visible = x - d >= 0 && std::abs(from_right.t - to_point.norm()) < 1e-6 * p.z();
      out.visible.at<uchar>(y, x) = visible ? 255 : 0;
    }
  }
  return out;
}

}  // namespace flexsight::testing_support

#include "host/synth/part_placement.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "host/synth/appearance.h"
#include "host/synth/synth_random.h"

namespace flexsight {
namespace {

using synth_detail::SynthRandom;

// A part that must be kept (no part kept yet) gets this many tries at least: it only
// needs one pixel in view.
constexpr int kFirstPartAttempts = 100;

bool visible_enough(int visible, int all, double cap) {
  // The same expression as visib_fract >= cap on the final annotation.
  return all > 0 && double(visible) / double(all) >= cap;
}

// The closest kept part per pixel, and each kept part's visible and total pixels.
class VisibilityLedger {
 public:
  VisibilityLedger(const cv::Size& size, double cap)
      : front_(cv::Mat::zeros(size, CV_32FC1)), owner_(size, CV_32SC1, cv::Scalar(-1)), cap_(cap) {}

  // Whether a part with amodal depth `patch` can join: it and every kept part stay at
  // or above the cap. Ties in depth go to the part already kept.
  bool admits(const AmodalPatch& patch) {
    lost_.assign(all_.size(), 0);
    int visible = 0;
    for_each_hit(patch, [&](float z, float& front, std::int32_t& owner) {
      if (front != 0.0f && !(z < front)) return;
      ++visible;
      if (owner >= 0) ++lost_[owner];
    });
    if (!visible_enough(visible, patch.pixels, cap_)) return false;
    for (size_t j = 0; j < all_.size(); ++j) {
      if (!visible_enough(visible_[j] - lost_[j], all_[j], cap_)) return false;
    }
    return true;
  }

  void add(const AmodalPatch& patch) {
    const std::int32_t id = static_cast<std::int32_t>(all_.size());
    int visible = 0;
    for_each_hit(patch, [&](float z, float& front, std::int32_t& owner) {
      if (front != 0.0f && !(z < front)) return;
      ++visible;
      if (owner >= 0) --visible_[owner];
      front = z;
      owner = id;
    });
    all_.push_back(patch.pixels);
    visible_.push_back(visible);
  }

 private:
  template <class Body>
  void for_each_hit(const AmodalPatch& patch, const Body& body) {
    for (int y = 0; y < patch.area.height; ++y) {
      const float* depth = patch.depth.ptr<float>(y);
      float* front = front_.ptr<float>(patch.area.y + y) + patch.area.x;
      std::int32_t* owner = owner_.ptr<std::int32_t>(patch.area.y + y) + patch.area.x;
      for (int x = 0; x < patch.area.width; ++x) {
        if (depth[x] > 0.0f) body(depth[x], front[x], owner[x]);
      }
    }
  }

  cv::Mat front_;  // CV_32FC1: depth of the closest kept part, 0 where none
  cv::Mat owner_;  // CV_32SC1: its index among the kept parts, -1 where none
  std::vector<int> all_, visible_, lost_;
  double cap_;
};

// A pose for `mesh`: projected diameter log-uniform in the settings' range, the centre
// of its bounding box uniform over the unrotated image, the rotation uniform; then
// turned with the camera.
Pose draw_pose(const FullSyntheticSettings& settings, const Mesh& mesh, const PinholeCamera& camera,
               const Eigen::Matrix3d& camera_rotation, SynthRandom& random) {
  const double size_px =
      random.log_uniform(settings.min_part_size, settings.max_part_size) * camera.width;
  const double z = camera.fx * double(mesh.diameter) / size_px;
  const double u = random.uniform(-0.5, camera.width - 0.5);
  const double v = random.uniform(-0.5, camera.height - 0.5);
  const double r1 = random.uniform(), r2 = random.uniform(), r3 = random.uniform();
  const Eigen::Matrix3d R0 = uniform_rotation(r1, r2, r3);
  const Eigen::Vector3d centre(z * (u - camera.cx) / camera.fx, z * (v - camera.cy) / camera.fy, z);
  Pose pose;
  pose.R = camera_rotation * R0;
  pose.t = camera_rotation * (centre - R0 * mesh.bounds.center().cast<double>());
  return pose;
}

}  // namespace

Eigen::Matrix3d uniform_rotation(double u1, double u2, double u3) {
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const Eigen::Quaterniond q(b * std::cos(2.0 * M_PI * u3), a * std::sin(2.0 * M_PI * u2),
                             a * std::cos(2.0 * M_PI * u2), b * std::sin(2.0 * M_PI * u3));
  return q.normalized().toRotationMatrix();
}

Placement place_parts(const FullSyntheticSettings& settings, const PartLibrary& library,
                      PooledScene& scene, const PinholeCamera& camera,
                      const Eigen::Matrix3d& camera_rotation, std::uint32_t seed,
                      std::int64_t image_index) {
  const CameraRayTable rays(camera);
  SynthRandom scene_random(seed, image_index, synth_detail::kStreamScene);
  const int count = scene_random.integer(settings.min_parts, settings.max_parts);
  VisibilityLedger ledger(cv::Size(camera.width, camera.height), settings.min_visible_fraction);
  Placement placement;
  for (int slot = 0; slot < count; ++slot) {
    // Each slot its own stream: its draws do not depend on the attempts of the others.
    SynthRandom random(seed, image_index, synth_detail::kStreamPart + std::uint32_t(slot));
    const int part = random.integer(0, library.size() - 1);
    const Mesh& mesh = *library.part(part).mesh;
    const Material material = draw_material(settings, random);
    const int attempts = placement.parts.empty()
                             ? std::max(settings.pose_attempts, kFirstPartAttempts)
                             : settings.pose_attempts;
    int instance = -1;
    bool kept = false;
    for (int attempt = 0; attempt < attempts && !kept; ++attempt) {
      const Pose pose = draw_pose(settings, mesh, camera, camera_rotation, random);
      if (instance < 0) {
        instance = scene.place(part, pose, material);
      } else {
        scene.scene().set_pose(instance, pose);
      }
      scene.scene().commit();
      AmodalPatch amodal = cast_alone(scene.scene(), instance, camera, rays);
      ++placement.attempts;
      if (ledger.admits(amodal)) {
        ledger.add(amodal);
        placement.parts.push_back({part, instance, std::move(amodal)});
        kept = true;
      }
    }
    if (!kept) {
      scene.park(instance);
      ++placement.dropped;
    }
  }
  scene.scene().commit();
  if (placement.parts.empty()) {
    throw std::runtime_error("full-synthetic image: no part could be placed in view");
  }
  return placement;
}

}  // namespace flexsight

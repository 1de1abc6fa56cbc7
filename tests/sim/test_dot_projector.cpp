// The dot projector: a dot lands where its direction meets the surface, red, and
// nothing lands where a part shadows the surface from the projector.
#include <gtest/gtest.h>

#include <cmath>

#include "host/io/input_error.h"
#include "host/render/mesh.h"
#include "host/sim/dot_projector.h"

using namespace flexsight;

namespace {

constexpr double kDeg = M_PI / 180.0;

std::shared_ptr<const Mesh> box_mesh(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
  std::vector<Eigen::Vector3f> p;
  for (int i = 0; i < 8; ++i) {
    p.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  }
  std::vector<std::array<std::uint32_t, 3>> t;
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    t.push_back({std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])});
    t.push_back({std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])});
  }
  return std::make_shared<const Mesh>(make_mesh("box", p, t));
}

PinholeCamera small_camera() {
  PinholeCamera camera;
  camera.width = 320;
  camera.height = 240;
  camera.fx = camera.fy = 300.0;
  camera.cx = 159.5;
  camera.cy = 119.5;
  return camera;
}

const Eigen::Vector3d kProjector(60.0, 0.0, 0.0);

}  // namespace

TEST(DotProjector, SpotProfile) {
  ProjectorSettings settings;
  settings.dots = 1;
  settings.dot_sigma_degrees = 0.1;
  const DotPattern pattern(settings);
  ASSERT_EQ(pattern.dots().size(), 1u);
  const Eigen::Vector2d dot = pattern.dots()[0];
  EXPECT_LE(std::abs(dot.x()), 17.5 * kDeg);
  EXPECT_LE(std::abs(dot.y()), 17.5 * kDeg);
  const double sigma = 0.1 * kDeg;
  EXPECT_NEAR(pattern.intensity(dot, 0.0), 1.0, 1e-12);
  EXPECT_NEAR(pattern.intensity(dot + Eigen::Vector2d(sigma, 0.0), 0.0), std::exp(-0.5), 1e-9);
  EXPECT_EQ(pattern.intensity(dot + Eigen::Vector2d(0.0, 4 * sigma), 0.0), 0.0);
  // Widened by a pixel's footprint: lower peak, same light in all.
  EXPECT_NEAR(pattern.intensity(dot, sigma), 0.5, 1e-12);
  // The layout is the seed's stream of draws with no state shared between patterns: a
  // 100-dot pattern built after another seed's starts with the 10-dot pattern's dots;
  // another seed gives another layout.
  settings.dots = 10;
  const DotPattern ten(settings);
  ProjectorSettings other = settings;
  other.pattern_seed = 2;
  other.dots = 100;
  const DotPattern other_seed(other);
  settings.dots = 100;
  const DotPattern hundred(settings);
  ASSERT_EQ(hundred.dots().size(), 100u);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(hundred.dots()[i], ten.dots()[i]) << "dot " << i;
  EXPECT_NE(hundred.dots()[7], other_seed.dots()[7]);
}

TEST(DotProjector, DotFallsWhereItsDirectionMeetsTheFloor) {
  RenderScene scene;
  Material white;
  white.albedo = Eigen::Vector3f::Constant(0.8f);
  scene.add_instance(scene.add_mesh(box_mesh({-2000, -2000, 1000}, {2000, 2000, 1010})), Pose{}, white);
  scene.commit();
  const PinholeCamera camera = small_camera();
  const RaycastImages images = raycast(scene, camera);
  for (std::uint32_t seed : {1u, 5u, 9u}) {
    ProjectorSettings settings;
    settings.dots = 1;
    settings.pattern_seed = seed;
    settings.dot_sigma_degrees = 0.3;  // a few pixels wide at 1 m, f = 300
    const DotPattern pattern(settings);
    const cv::Mat radiance = projector_radiance(scene, images, camera, kProjector, pattern, 2);
    // Where the dot's direction meets the floor (z = 1000), seen by the camera.
    const Eigen::Vector2d dot = pattern.dots()[0];
    const Eigen::Vector3d hit = kProjector + 1000.0 * Eigen::Vector3d(std::tan(dot.x()), std::tan(dot.y()), 1.0);
    const Eigen::Vector2d expected = camera.project(hit);
    // The red peak and its centroid.
    cv::Point peak;
    std::vector<cv::Mat> channels;
    cv::split(radiance, channels);
    double max_red = 0.0;
    cv::minMaxLoc(channels[0], nullptr, &max_red, nullptr, &peak);
    ASSERT_GT(max_red, 0.3) << seed;
    double sum = 0.0, sx = 0.0, sy = 0.0;
    for (int y = std::max(0, peak.y - 6); y <= std::min(camera.height - 1, peak.y + 6); ++y) {
      for (int x = std::max(0, peak.x - 6); x <= std::min(camera.width - 1, peak.x + 6); ++x) {
        const double r = channels[0].at<float>(y, x);
        sum += r;
        sx += r * x;
        sy += r * y;
      }
    }
    EXPECT_NEAR(sx / sum, expected.x(), 0.25) << seed;
    EXPECT_NEAR(sy / sum, expected.y(), 0.25) << seed;
    // Red: the green and blue channels far weaker; nothing far from the dot.
    EXPECT_LT(channels[1].at<float>(peak), 0.2 * max_red);
    EXPECT_LE(cv::countNonZero(channels[0] > 1e-3 * max_red), 15 * 15);
  }
}

TEST(DotProjector, ShadowOfAPartHasNoDots) {
  RenderScene scene;
  Material grey;
  grey.albedo = Eigen::Vector3f::Constant(0.6f);
  const int floor = scene.add_instance(scene.add_mesh(box_mesh({-2000, -2000, 1000}, {2000, 2000, 1010})), Pose{}, grey);
  const Eigen::Vector3f lo(0, -60, 500), hi(120, 60, 520);
  const int block = scene.add_instance(scene.add_mesh(box_mesh(lo, hi)), Pose{}, grey);
  scene.commit();
  const PinholeCamera camera = small_camera();
  const RaycastImages images = raycast(scene, camera);
  ProjectorSettings settings;
  settings.dots = 20000;
  settings.dot_sigma_degrees = 0.05;
  const DotPattern pattern(settings);
  const cv::Mat radiance = projector_radiance(scene, images, camera, kProjector, pattern, 2);

  // Whether the segment from a floor point to the projector passes through the block
  // (slab test).
  const auto shadowed = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = kProjector - p;
    double t0 = 0.0, t1 = 1.0;
    for (int k = 0; k < 3; ++k) {
      const double a = (lo[k] - p[k]) / d[k], b = (hi[k] - p[k]) / d[k];
      t0 = std::max(t0, std::min(a, b));
      t1 = std::min(t1, std::max(a, b));
    }
    return t0 < t1;
  };
  int shadow_pixels = 0, shadow_lit = 0, open_pixels = 0, open_lit = 0, block_lit = 0;
  for (int y = 0; y < camera.height; ++y) {
    for (int x = 0; x < camera.width; ++x) {
      const cv::Vec3f& q = images.point.at<cv::Vec3f>(y, x);
      const bool lit = radiance.at<cv::Vec3f>(y, x)[0] > 0.0f;
      const int id = images.instance.at<int>(y, x);
      if (id == block) block_lit += lit;
      if (id != floor) continue;
      // Away from the shadow's edge by a dot's reach and the pixel (2 mm).
      const Eigen::Vector3d p(q[0], q[1], q[2]);
      bool near_edge = false;
      for (double dx : {-3.0, 3.0}) {
        for (double dy : {-3.0, 3.0}) {
          near_edge |= shadowed(p + Eigen::Vector3d(dx, dy, 0)) != shadowed(p);
        }
      }
      if (near_edge) continue;
      if (shadowed(p)) {
        ++shadow_pixels;
        shadow_lit += lit;
      } else if (std::abs(p.x() - 60.0) < 300.0 && std::abs(p.y()) < 300.0) {
        ++open_pixels;
        open_lit += lit;
      }
    }
  }
  ASSERT_GT(shadow_pixels, 1000);
  EXPECT_EQ(shadow_lit, 0);
  // Outside the shadow, within the projector's field, dots everywhere.
  ASSERT_GT(open_pixels, 5000);
  EXPECT_GT(open_lit, open_pixels / 10);
  EXPECT_GT(block_lit, 100);
}

TEST(DotProjector, BadSettingsNameTheirOption) {
  ProjectorSettings settings;
  settings.dots = 0;
  EXPECT_THROW(settings.check(), InputError);
  settings = {};
  settings.fov_degrees = 180.0;
  try {
    settings.check();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--projector-fov"), std::string::npos);
  }
  settings = {};
  settings.dot_sigma_degrees = 0.0;
  EXPECT_THROW(settings.check(), InputError);
}

// Shading against its formulas: Lambert and ambient on a plane, a hard shadow where the
// segment to the light crosses an occluder, a penumbra with a light of some size, a
// spot's cone, the highlight's peak, the sRGB picture, the seed, and bad lighting; and
// against a one-ray-at-a-time reference, to the bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "host/io/input_error.h"
#include "host/render/raycaster.h"
#include "host/render/shading.h"
#include "kernels/common/counter_rng.h"
#include "tests/render/render_test_support.h"

using namespace flexsight;
using namespace flexsight::testing_support;

namespace {

Eigen::Vector3f at(const cv::Mat& image, int u, int v) {
  const cv::Vec3f& p = image.at<cv::Vec3f>(v, u);
  return {p[0], p[1], p[2]};
}

PinholeCamera small_camera() {
  PinholeCamera camera;
  camera.width = 120;
  camera.height = 90;
  camera.fx = camera.fy = 100.0;
  camera.cx = 59.5;
  camera.cy = 44.5;
  return camera;
}

Material matte(const Eigen::Vector3f& albedo) {
  Material material;
  material.albedo = albedo;
  material.specular = 0.0f;
  return material;
}

// A floor square facing the camera at z = 1000, optionally an occluder square between
// it and the light.
struct FloorScene {
  RenderScene scene;
  RaycastImages images;
  FloorScene(const PinholeCamera& camera, bool occluder, const Material& material) {
    scene.add_instance(scene.add_mesh(square_mesh(2000.0f)), make_pose(0, {0, 0, 1}, {0, 0, 1000}),
                       material);
    if (occluder) {
      scene.add_instance(scene.add_mesh(square_mesh(60.0f)), make_pose(0, {0, 0, 1}, {0, 0, 800}),
                         material);
    }
    scene.commit();
    images = raycast(scene, camera);
  }
};

}  // namespace

TEST(Shading, LambertAndAmbientOnAPlaneFollowTheFormula) {
  const PinholeCamera camera = small_camera();
  const Eigen::Vector3f albedo(0.5f, 0.6f, 0.7f);
  FloorScene floor(camera, false, matte(albedo));
  ShadingOptions options;
  options.ambient = 0.1f;
  options.lights[0].position = {300.0f, -500.0f, 200.0f};
  options.lights[0].intensity = {0.9f, 0.8f, 0.7f};
  const cv::Mat radiance = shade_linear(floor.scene, floor.images, options);
  for (int v = 0; v < camera.height; v += 7) {
    for (int u = 0; u < camera.width; u += 5) {
      const Eigen::Vector3f p = at(floor.images.point, u, v);
      const Eigen::Vector3f l = (options.lights[0].position - p).normalized();
      const float lambert = std::max(0.0f, Eigen::Vector3f(0, 0, -1).dot(l));
      const Eigen::Vector3f expected =
          albedo * options.ambient + lambert * options.lights[0].intensity.cwiseProduct(albedo);
      EXPECT_LT((at(radiance, u, v) - expected).norm(), 1e-5f) << u << ", " << v;
    }
  }
}

// A 120 mm square at 800 mm in front of the floor at 1000 mm, lit from the side: a floor
// point is in shadow exactly where its segment to the light crosses the square.
TEST(Shading, HardShadowIsWhereTheSegmentToTheLightCrossesTheOccluder) {
  const PinholeCamera camera = small_camera();
  const Eigen::Vector3f albedo(0.6f, 0.6f, 0.6f);
  FloorScene floor(camera, true, matte(albedo));
  ShadingOptions options;
  options.ambient = 0.2f;
  options.lights[0].position = {-250.0f, 100.0f, 300.0f};
  const cv::Mat radiance = shade_linear(floor.scene, floor.images, options);
  int shadowed = 0, lit = 0;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      if (floor.images.instance.at<std::int32_t>(v, u) != 0) continue;  // the floor only
      const Eigen::Vector3f p = at(floor.images.point, u, v);
      const Eigen::Vector3f& light = options.lights[0].position;
      const float s = (800.0f - p.z()) / (light.z() - p.z());
      const Eigen::Vector3f q = p + s * (light - p);
      const float inside = 60.0f - q.head<2>().cwiseAbs().maxCoeff();
      const float lambert = Eigen::Vector3f(0, 0, -1).dot((light - p).normalized());
      const Eigen::Vector3f ambient = options.ambient * albedo;
      const Eigen::Vector3f full =
          ambient + lambert * options.lights[0].intensity.cwiseProduct(albedo);
      if (inside > 0.5f) {
        EXPECT_LT((at(radiance, u, v) - ambient).norm(), 1e-6f) << u << ", " << v;
        ++shadowed;
      } else if (inside < -0.5f) {
        EXPECT_LT((at(radiance, u, v) - full).norm(), 1e-5f) << u << ", " << v;
        ++lit;
      }
    }
  }
  EXPECT_GT(shadowed, 100);
  EXPECT_GT(lit, 2000);
}

// The same scene under a light of radius 60 mm: between the umbra and full light lies a
// penumbra, and nothing is darker than the ambient or brighter than full light.
TEST(Shading, SoftShadowsHaveAPenumbra) {
  const PinholeCamera camera = small_camera();
  const Eigen::Vector3f albedo(0.6f, 0.6f, 0.6f);
  FloorScene floor(camera, true, matte(albedo));
  ShadingOptions options;
  options.ambient = 0.2f;
  options.lights[0].position = {-250.0f, 100.0f, 300.0f};
  options.lights[0].radius = 60.0f;
  options.shadow_samples = 16;
  const cv::Mat radiance = shade_linear(floor.scene, floor.images, options);
  options.lights[0].radius = 0.0f;
  const cv::Mat hard = shade_linear(floor.scene, floor.images, options);
  int penumbra = 0, differ = 0;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      if (floor.images.instance.at<std::int32_t>(v, u) != 0) continue;
      const Eigen::Vector3f p = at(floor.images.point, u, v);
      const float lambert =
          Eigen::Vector3f(0, 0, -1).dot((options.lights[0].position - p).normalized());
      const float ambient = options.ambient * albedo.x();
      const float full = ambient + lambert * options.lights[0].intensity.x() * albedo.x();
      const float value = at(radiance, u, v).x();
      EXPECT_GE(value, ambient - 1e-6f);
      EXPECT_LE(value, full + 1e-5f);
      if (value > ambient + 1e-3f && value < full - 1e-3f) ++penumbra;
      if (std::abs(value - at(hard, u, v).x()) > 1e-3f) ++differ;
    }
  }
  EXPECT_GT(penumbra, 100);
  EXPECT_GT(differ, 100);
}

TEST(Shading, SpotLightsOnlyItsCone) {
  const PinholeCamera camera = small_camera();
  const Eigen::Vector3f albedo(0.5f, 0.5f, 0.5f);
  FloorScene floor(camera, false, matte(albedo));
  ShadingOptions options;
  options.ambient = 0.1f;
  Light& spot = options.lights[0];
  spot.position = {0.0f, 0.0f, 0.0f};
  spot.direction = {0.3f, 0.0f, 1.0f};
  spot.cone_degrees = 10.0f;
  spot.falloff_degrees = 2.0f;
  const cv::Mat radiance = shade_linear(floor.scene, floor.images, options);
  const float cos_inner = std::cos(8.0f * float(M_PI) / 180.0f);
  const float cos_outer = std::cos(10.0f * float(M_PI) / 180.0f);
  int inside = 0, outside = 0;
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3f p = at(floor.images.point, u, v);
      const float c = p.normalized().dot(spot.direction.normalized());
      const float lambert = Eigen::Vector3f(0, 0, -1).dot(-p.normalized());
      const float value = at(radiance, u, v).x();
      if (c > cos_inner + 1e-4f) {
        EXPECT_NEAR(value, 0.1f * 0.5f + lambert * 0.8f * 0.5f, 1e-5f);
        ++inside;
      } else if (c < cos_outer - 1e-4f) {
        EXPECT_NEAR(value, 0.1f * 0.5f, 1e-6f);
        ++outside;
      }
    }
  }
  EXPECT_GT(inside, 50);
  EXPECT_GT(outside, 1000);
}

// Lit from the camera alone with no diffuse part, a tilted plane shows only the
// highlight, brightest where its normal points back at the camera: the foot of the
// perpendicular from the camera centre.
TEST(Shading, HighlightPeaksWhereTheNormalFacesTheCameraLight) {
  PinholeCamera camera = small_camera();
  Material shiny;
  shiny.albedo = Eigen::Vector3f::Zero();
  shiny.specular = 1.0f;
  shiny.shininess = 60.0f;
  const Pose pose = make_pose(12.0, {1.0, -0.7, 0.0}, {10.0, 5.0, 600.0});
  RenderScene scene;
  scene.add_instance(scene.add_mesh(square_mesh(1000.0f)), pose, shiny);
  scene.commit();
  const RaycastImages images = raycast(scene, camera);
  ShadingOptions options;
  options.lights.clear();
  options.camera_light = true;
  options.ambient = 0.0f;
  const cv::Mat radiance = shade_linear(scene, images, options);
  cv::Point peak;
  cv::Mat channels[3];
  cv::split(radiance, channels);
  cv::minMaxLoc(channels[0], nullptr, nullptr, nullptr, &peak);
  const Eigen::Vector3d n = pose.R.col(2);
  const Eigen::Vector2d foot = camera.project(n.dot(pose.t) * n);
  EXPECT_NEAR(peak.x, foot.x(), 1.0);
  EXPECT_NEAR(peak.y, foot.y(), 1.0);
  EXPECT_NEAR(channels[0].at<float>(peak), options.camera_light_intensity.x(), 1e-3f);
}

// The picture: the background where no surface is, sRGB-encoded radiance elsewhere.
TEST(Shading, PictureIsSrgbOverTheBackground) {
  const PinholeCamera camera = small_camera();
  RenderScene scene;
  scene.add_instance(scene.add_mesh(square_mesh(100.0f)), make_pose(0, {0, 0, 1}, {0, 0, 1000}),
                     matte({1.0f, 0.5f, 0.0f}));
  scene.commit();
  const RaycastImages images = raycast(scene, camera);
  ShadingOptions options;
  options.lights.clear();
  options.camera_light = true;
  options.camera_light_intensity = {0.0f, 0.0f, 0.0f};
  options.ambient = 1.0f;
  options.background = {10, 20, 30};
  const cv::Mat rgb = shade(scene, images, options);
  ASSERT_EQ(rgb.type(), CV_8UC3);
  EXPECT_EQ(rgb.at<cv::Vec3b>(45, 60), cv::Vec3b(255, 188, 0));  // sRGB(0.5) = 188
  EXPECT_EQ(rgb.at<cv::Vec3b>(0, 0), cv::Vec3b(10, 20, 30));
}

TEST(Shading, SameSeedSameBytesOtherSeedOtherBytes) {
  const PinholeCamera camera = small_camera();
  FloorScene floor(camera, true, matte({0.6f, 0.6f, 0.6f}));
  ShadingOptions options;
  options.lights[0].position = {-250.0f, 100.0f, 300.0f};
  options.lights[0].radius = 60.0f;
  options.shadow_samples = 3;
  const cv::Mat first = shade(floor.scene, floor.images, options);
  EXPECT_TRUE(same_mat_bytes(first, shade(floor.scene, floor.images, options)));
  options.seed = 2;
  EXPECT_FALSE(same_mat_bytes(first, shade(floor.scene, floor.images, options)));
}

TEST(Shading, TintedGreysAreGreyDistinctAndRepeatable) {
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector3f albedo = tinted_grey(5, i);
    EXPECT_EQ(albedo, tinted_grey(5, i));
    EXPECT_NE(albedo, tinted_grey(5, i + 1));
    const float grey = albedo.mean();
    EXPECT_GE(grey, 0.43f);
    EXPECT_LE(grey, 0.77f);
    EXPECT_LE((albedo.array() / grey - 1.0f).abs().maxCoeff(), 0.09f);
  }
}

TEST(Shading, RejectsImpossibleLighting) {
  const auto message = [](const ShadingOptions& options) -> std::string {
    try {
      options.check();
    } catch (const InputError& error) {
      return error.what();
    }
    return "accepted";
  };
  ShadingOptions options;
  EXPECT_EQ(message(options), "accepted");
  options.lights.assign(4, Light{});
  EXPECT_EQ(message(options).rfind("lighting: 4 lights", 0), 0u);
  options.lights.clear();
  EXPECT_EQ(message(options).rfind("lighting: no light", 0), 0u);
  options.camera_light = true;
  EXPECT_EQ(message(options), "accepted");
  options.lights.assign(1, Light{});
  options.lights[0].radius = -1.0f;
  EXPECT_EQ(message(options).rfind("lighting: light 0: radius", 0), 0u);
  options.lights[0].radius = 0.0f;
  options.lights[0].cone_degrees = 0.0f;
  EXPECT_EQ(message(options).rfind("lighting: light 0: cone", 0), 0u);
  options.lights[0].cone_degrees = 180.0f;
  options.shadow_samples = 0;
  EXPECT_EQ(message(options).rfind("lighting: shadow samples", 0), 0u);
}

namespace {

// One pixel shaded as docs/render.md describes it, with one rtcOccluded1 per shadow ray
// and every cosine computed where it is needed: the reference for shade_linear, which
// casts its shadow rays in packets of sixteen and computes a spot's cone once.
Eigen::Vector3f reference_pixel(const RenderScene& scene, const RaycastImages& images,
                                const ShadingOptions& options, int u, int v) {
  constexpr float kPi = 3.14159265358979323846f;
  const Eigen::Vector3f point = at(images.point, u, v);
  const Eigen::Vector3f normal = at(images.normal, u, v);
  const Eigen::Vector3f geometric = at(images.geometric_normal, u, v);
  const Material& material = scene.instance(images.instance.at<std::int32_t>(v, u)).material;
  const float offset = 1e-5f * point.cwiseAbs().maxCoeff() + 1e-4f;
  const Eigen::Vector3f origin = point + offset * geometric;
  const fs_u32 pixel = fs_u32(v) * fs_u32(images.depth.cols) + fs_u32(u);
  const auto blocked = [&](const Eigen::Vector3f& target) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    ray.org_x = origin.x();
    ray.org_y = origin.y();
    ray.org_z = origin.z();
    const Eigen::Vector3f direction = target - origin;
    ray.dir_x = direction.x();
    ray.dir_y = direction.y();
    ray.dir_z = direction.z();
    ray.tnear = 0.0f;
    ray.tfar = 1.0f - 1e-4f;
    ray.time = 0.0f;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
    rtcOccluded1(scene.embree_scene(), &context, &ray);
    return ray.tfar < 0.0f;
  };
  std::vector<Light> lights = options.lights;
  if (options.camera_light) {
    Light camera;
    camera.position = Eigen::Vector3f::Zero();
    camera.intensity = options.camera_light_intensity;
    lights.push_back(camera);
  }
  const Eigen::Vector3f to_eye = -point.normalized();
  Eigen::Vector3f colour = options.ambient * material.albedo;
  for (size_t l = 0; l < lights.size(); ++l) {
    const Light& light = lights[l];
    const Eigen::Vector3f to_light = (light.position - point).normalized();
    const float lambert = normal.dot(to_light);
    if (lambert <= 0.0f || geometric.dot(to_light) <= 0.0f) continue;
    float spot = 1.0f;
    if (light.cone_degrees < 180.0f) {
      const float outer = std::cos(light.cone_degrees * kPi / 180.0f);
      const float inner =
          std::cos(std::max(light.cone_degrees - light.falloff_degrees, 0.0f) * kPi / 180.0f);
      const float c = (-to_light).dot(light.direction.normalized());
      if (c <= outer) continue;
      if (!(c >= inner || inner <= outer)) {
        const float s = (c - outer) / (inner - outer);
        spot = s * s * (3.0f - 2.0f * s);
      }
    }
    float visible = 1.0f;
    if (options.shadows && l < options.lights.size()) {
      if (light.radius <= 0.0f) {
        visible = blocked(light.position) ? 0.0f : 1.0f;
      } else {
        const Eigen::Vector3f w = (light.position - origin).normalized();
        const Eigen::Vector3f helper =
            std::abs(w.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
        const Eigen::Vector3f a = w.cross(helper).normalized();
        const Eigen::Vector3f b = w.cross(a);
        int unblocked = 0;
        for (int k = 0; k < options.shadow_samples; ++k) {
          // The jitter's key: (seed, pixel, light, sample).
          fs_u32 h = fs_hash(options.seed ^ 0x5AD0F00DU);
          h = fs_hash(h ^ pixel);
          h = fs_hash(h ^ (fs_u32(l) * 0x10000U + fs_u32(k)));
          const float j0 = fs_u32_to_unit(h), j1 = fs_u32_to_unit(fs_hash(h ^ 0x68E31DA4U));
          const float r = light.radius * std::sqrt(j0);
          const float phi = 2.0f * kPi * (float(k) + j1) / float(options.shadow_samples);
          const Eigen::Vector3f target =
              light.position + r * (std::cos(phi) * a + std::sin(phi) * b);
          if (!blocked(target)) ++unblocked;
        }
        visible = float(unblocked) / float(options.shadow_samples);
      }
    }
    if (visible <= 0.0f) continue;
    const Eigen::Vector3f half = (to_light + to_eye).normalized();
    const float highlight =
        material.specular * std::pow(std::max(normal.dot(half), 0.0f), material.shininess);
    colour += (visible * spot) * light.intensity.cwiseProduct(lambert * material.albedo +
                                                              Eigen::Vector3f::Constant(highlight));
  }
  return colour;
}

}  // namespace

// T-LESS parts over a floor under three lights (hard, soft, and a soft spot whose cone
// edge crosses the parts) and the camera light, 5 soft-shadow rays (packets that end
// part full): every pixel is the same float bits as the reference's, on 1 and 3 threads.
TEST(Shading, ShadowRayPacketsGiveTheSameFloatsAsOneRayAtATime) {
  RenderScene scene;
  const char* objects[] = {"05", "11", "26"};
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(file_present(tless_cad_path(objects[i])));
    const int mesh = scene.add_mesh(
        std::make_shared<const Mesh>(load_mesh(tless_cad_path(objects[i]).string())));
    Material material;
    material.albedo = tinted_grey(4, i);
    material.shininess = 12.0f + 40.0f * i;
    scene.add_instance(mesh,
                       make_pose(50.0 * i, {0.5, 1.0, i - 1.0},
                                 {-50.0 + 50.0 * i, 15.0 * (i % 2), 480.0 + 20 * i}),
                       material);
  }
  scene.add_instance(scene.add_mesh(square_mesh(400.0f)), make_pose(0, {0, 0, 1}, {0, 0, 540}),
                     matte({0.5f, 0.5f, 0.5f}));
  scene.commit();
  PinholeCamera camera;
  camera.width = 133;
  camera.height = 101;
  camera.fx = camera.fy = 130.0;
  camera.cx = 66.2;
  camera.cy = 49.9;
  const RaycastImages images = raycast(scene, camera);

  ShadingOptions options;
  options.lights.resize(3);
  options.lights[0].position = {-300.0f, -500.0f, 100.0f};
  options.lights[1].position = {250.0f, -200.0f, 50.0f};
  options.lights[1].radius = 50.0f;
  options.lights[2].position = {0.0f, 400.0f, 0.0f};
  options.lights[2].radius = 30.0f;
  options.lights[2].direction = Eigen::Vector3f(0.0f, -400.0f, 500.0f).normalized();
  options.lights[2].cone_degrees = 20.0f;
  options.lights[2].falloff_degrees = 6.0f;
  options.camera_light = true;
  options.shadow_samples = 5;
  options.seed = 11;
  ShadingOptions unshadowed = options;
  unshadowed.shadows = false;
  unshadowed.threads = 1;
  const cv::Mat without = shade_linear(scene, images, unshadowed);
  for (int threads : {1, 3}) {
    options.threads = threads;
    const cv::Mat radiance = shade_linear(scene, images, options);
    int surfaces = 0, differ = 0, shadowed = 0;
    for (int v = 0; v < camera.height; ++v) {
      for (int u = 0; u < camera.width; ++u) {
        if (images.instance.at<std::int32_t>(v, u) < 0) continue;
        ++surfaces;
        const Eigen::Vector3f expected = reference_pixel(scene, images, options, u, v);
        const Eigen::Vector3f got = at(radiance, u, v);
        if (std::memcmp(expected.data(), got.data(), sizeof(float) * 3) != 0) ++differ;
        if (got != at(without, u, v)) ++shadowed;
      }
    }
    EXPECT_EQ(differ, 0) << threads << " threads";
    EXPECT_GT(surfaces, 5000);
    EXPECT_GT(shadowed, 500);
  }
}

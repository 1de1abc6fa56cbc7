#include "host/render/shading.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "host/io/input_error.h"
#include "host/render/tiles.h"
#include "kernels/common/counter_rng.h"

namespace flexsight {
namespace {

constexpr float kPi = 3.14159265358979323846f;

// Keys of the module's random numbers, one stream per purpose.
constexpr fs_u32 kKeyShadow = 0x5AD0F00DU;
constexpr fs_u32 kKeyAlbedo = 0xA1BED000U;

// Two uniforms in [0, 1) for sample `sample` of light `light` at pixel `pixel`: a hash
// of the key, never the state of a generator, so tiles may run in any order.
std::array<float, 2> shadow_jitter(fs_u32 seed, fs_u32 pixel, fs_u32 light, fs_u32 sample) {
  fs_u32 h = fs_hash(seed ^ kKeyShadow);
  h = fs_hash(h ^ pixel);
  h = fs_hash(h ^ (light * 0x10000U + sample));
  return {fs_u32_to_unit(h), fs_u32_to_unit(fs_hash(h ^ 0x68E31DA4U))};
}

bool finite_nonnegative(const Eigen::Vector3f& v) { return v.allFinite() && v.minCoeff() >= 0.0f; }

// A shadow ray's start: the hit point moved off its surface, against self-hits, by
// about 100 float steps at that distance from the camera (10 um at 1 m).
Eigen::Vector3f shadow_origin(const Eigen::Vector3f& point,
                              const Eigen::Vector3f& geometric_normal) {
  const float offset = 1e-5f * point.cwiseAbs().maxCoeff() + 1e-4f;
  return point + offset * geometric_normal;
}

bool occluded(RTCScene scene, const Eigen::Vector3f& origin, const Eigen::Vector3f& target) {
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
  // The direction spans the whole way to the light: parameters up to just below 1.
  ray.tnear = 0.0f;
  ray.tfar = 1.0f - 1e-4f;
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  rtcOccluded1(scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf when something blocks the ray
}

// The light's own shading: a spot's cone, with a smooth edge.
float spot_factor(const Light& light, const Eigen::Vector3f& from_light) {
  if (light.cone_degrees >= 180.0f) return 1.0f;
  const float outer = std::cos(light.cone_degrees * kPi / 180.0f);
  const float inner =
      std::cos(std::max(light.cone_degrees - light.falloff_degrees, 0.0f) * kPi / 180.0f);
  const float c = from_light.dot(light.direction.normalized());
  if (c <= outer) return 0.0f;
  if (c >= inner || inner <= outer) return 1.0f;
  const float s = (c - outer) / (inner - outer);
  return s * s * (3.0f - 2.0f * s);
}

// Fraction of the light that reaches `point`: 1 or 0 for a point light, the share of
// unblocked rays to jittered points of the disc (facing the point) otherwise. The
// samples are stratified in angle so that few of them already cover the disc.
float visibility(RTCScene scene, const ShadingOptions& options, const Light& light,
                 fs_u32 light_index, fs_u32 pixel, const Eigen::Vector3f& origin) {
  if (light.radius <= 0.0f) return occluded(scene, origin, light.position) ? 0.0f : 1.0f;
  const Eigen::Vector3f w = (light.position - origin).normalized();
  const Eigen::Vector3f helper =
      std::abs(w.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
  const Eigen::Vector3f a = w.cross(helper).normalized();
  const Eigen::Vector3f b = w.cross(a);
  int unblocked = 0;
  for (int k = 0; k < options.shadow_samples; ++k) {
    const auto jitter = shadow_jitter(options.seed, pixel, light_index, fs_u32(k));
    const float r = light.radius * std::sqrt(jitter[0]);
    const float phi = 2.0f * kPi * (float(k) + jitter[1]) / float(options.shadow_samples);
    const Eigen::Vector3f target = light.position + r * (std::cos(phi) * a + std::sin(phi) * b);
    if (!occluded(scene, origin, target)) ++unblocked;
  }
  return float(unblocked) / float(options.shadow_samples);
}

// sRGB encoding by a table over [0, 1]: the same bytes on every machine, and no pow()
// per pixel.
class SrgbTable {
 public:
  SrgbTable() {
    for (int i = 0; i < kSize; ++i) {
      const double v = double(i) / (kSize - 1);
      const double s = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
      table_[i] = static_cast<std::uint8_t>(std::lround(255.0 * s));
    }
  }
  std::uint8_t operator()(float linear) const {
    const float clipped = std::min(std::max(linear, 0.0f), 1.0f);
    return table_[static_cast<int>(clipped * float(kSize - 1) + 0.5f)];
  }

 private:
  static constexpr int kSize = 4096;
  std::uint8_t table_[kSize];
};

}  // namespace

void ShadingOptions::check() const {
  const auto fail = [](const std::string& problem) { throw InputError("lighting", problem); };
  if (lights.size() > 3) fail(std::to_string(lights.size()) + " lights; at most 3");
  if (lights.empty() && !camera_light) fail("no light (add one or the camera light)");
  for (size_t i = 0; i < lights.size(); ++i) {
    const Light& light = lights[i];
    const std::string name = "light " + std::to_string(i) + ": ";
    if (!light.position.allFinite()) fail(name + "position is not finite");
    if (!finite_nonnegative(light.intensity)) fail(name + "intensity must be finite and >= 0");
    if (!(std::isfinite(light.radius) && light.radius >= 0.0f)) fail(name + "radius must be >= 0");
    if (!(light.cone_degrees > 0.0f && light.cone_degrees <= 180.0f)) {
      fail(name + "cone must be in (0, 180] degrees");
    }
    if (!(light.falloff_degrees >= 0.0f && light.falloff_degrees <= 180.0f)) {
      fail(name + "falloff must be in [0, 180] degrees");
    }
    if (light.cone_degrees < 180.0f &&
        !(light.direction.allFinite() && light.direction.norm() > 0.0f)) {
      fail(name + "a spot light needs a direction");
    }
  }
  if (!finite_nonnegative(camera_light_intensity)) fail("camera light intensity must be >= 0");
  if (!(std::isfinite(ambient) && ambient >= 0.0f)) fail("ambient must be finite and >= 0");
  if (shadow_samples < 1 || shadow_samples > 256) fail("shadow samples must be in 1..256");
}

cv::Mat shade_linear(const RenderScene& scene, const RaycastImages& images,
                     const ShadingOptions& options) {
  options.check();
  if (!scene.committed()) {
    throw std::logic_error("shading needs RenderScene::commit() after the last change");
  }
  const int width = images.depth.cols, height = images.depth.rows;
  cv::Mat radiance = cv::Mat::zeros(height, width, CV_32FC3);
  std::vector<Light> lights = options.lights;
  const size_t scene_lights = lights.size();
  if (options.camera_light) {
    Light camera;
    camera.position = Eigen::Vector3f::Zero();
    camera.intensity = options.camera_light_intensity;
    lights.push_back(camera);
  }
  const RTCScene top = scene.embree_scene();

  render_detail::for_each_tile(
      cv::Rect(0, 0, width, height), options.threads, [&](int x0, int y0, int x1, int y1) {
        for (int y = y0; y < y1; ++y) {
          for (int x = x0; x < x1; ++x) {
            const int id = images.instance.at<std::int32_t>(y, x);
            if (id < 0) continue;
            const Material& material = scene.instance(id).material;
            const cv::Vec3f& p = images.point.at<cv::Vec3f>(y, x);
            const cv::Vec3f& ns = images.normal.at<cv::Vec3f>(y, x);
            const cv::Vec3f& ng = images.geometric_normal.at<cv::Vec3f>(y, x);
            const Eigen::Vector3f point(p[0], p[1], p[2]);
            const Eigen::Vector3f normal(ns[0], ns[1], ns[2]);
            const Eigen::Vector3f geometric(ng[0], ng[1], ng[2]);
            const Eigen::Vector3f to_eye = -point.normalized();
            const Eigen::Vector3f origin = shadow_origin(point, geometric);
            const fs_u32 pixel = fs_u32(y) * fs_u32(width) + fs_u32(x);

            Eigen::Vector3f colour = options.ambient * material.albedo;
            for (size_t l = 0; l < lights.size(); ++l) {
              const Light& light = lights[l];
              const Eigen::Vector3f to_light = (light.position - point).normalized();
              const float lambert = normal.dot(to_light);
              // A light behind the triangle itself lights nothing there, whatever the
              // interpolated normal says.
              if (lambert <= 0.0f || geometric.dot(to_light) <= 0.0f) continue;
              const float spot = spot_factor(light, -to_light);
              if (spot <= 0.0f) continue;
              const bool casts_shadows = options.shadows && l < scene_lights;
              const float visible =
                  casts_shadows ? visibility(top, options, light, fs_u32(l), pixel, origin) : 1.0f;
              if (visible <= 0.0f) continue;
              const Eigen::Vector3f half = (to_light + to_eye).normalized();
              const float highlight = material.specular * std::pow(std::max(normal.dot(half), 0.0f),
                                                                   material.shininess);
              colour += (visible * spot) *
                        light.intensity.cwiseProduct(lambert * material.albedo +
                                                     Eigen::Vector3f::Constant(highlight));
            }
            radiance.at<cv::Vec3f>(y, x) = {colour.x(), colour.y(), colour.z()};
          }
        }
      });
  return radiance;
}

cv::Mat shade(const RenderScene& scene, const RaycastImages& images,
              const ShadingOptions& options) {
  const cv::Mat radiance = shade_linear(scene, images, options);
  static const SrgbTable srgb;
  cv::Mat rgb(radiance.size(), CV_8UC3);
  for (int y = 0; y < rgb.rows; ++y) {
    for (int x = 0; x < rgb.cols; ++x) {
      if (images.instance.at<std::int32_t>(y, x) < 0) {
        rgb.at<cv::Vec3b>(y, x) = options.background;
        continue;
      }
      const cv::Vec3f& c = radiance.at<cv::Vec3f>(y, x);
      rgb.at<cv::Vec3b>(y, x) = {srgb(c[0]), srgb(c[1]), srgb(c[2])};
    }
  }
  return rgb;
}

Eigen::Vector3f tinted_grey(std::uint32_t seed, int instance) {
  fs_u32 h = fs_hash(fs_hash(seed ^ kKeyAlbedo) ^ fs_u32(instance));
  const float grey = 0.45f + 0.30f * fs_u32_to_unit(h);
  Eigen::Vector3f albedo;
  for (int c = 0; c < 3; ++c) {
    h = fs_hash(h ^ fs_u32(c + 1));
    albedo[c] = grey * (1.0f + 0.08f * (fs_u32_to_unit(h) - 0.5f));
  }
  return albedo;
}

}  // namespace flexsight

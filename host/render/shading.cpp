#include "host/render/shading.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "host/io/input_error.h"
#include "host/render/shadow_packets.h"
#include "host/render/tiles.h"
#include "kernels/common/counter_rng.h"

namespace flexsight {
namespace {

using render_detail::ShadowPackets;

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

// A light as the shading loop reads it: its spot cone's cosines computed once (the same
// floats as computed per pixel, so the same bytes), and whether it casts shadows.
struct LightView {
  const Light* light;
  bool casts_shadows;
  bool spot;
  float outer, inner;  // cosines of the cone's edge and of where the falloff begins
  Eigen::Vector3f direction;
};

LightView view_light(const Light& light, bool casts_shadows) {
  LightView view{&light, casts_shadows, light.cone_degrees < 180.0f, 1.0f, 1.0f,
                 Eigen::Vector3f::UnitZ()};
  if (view.spot) {
    view.outer = std::cos(light.cone_degrees * kPi / 180.0f);
    view.inner =
        std::cos(std::max(light.cone_degrees - light.falloff_degrees, 0.0f) * kPi / 180.0f);
    view.direction = light.direction.normalized();
  }
  return view;
}

// The light's own shading: a spot's cone, with a smooth edge.
float spot_factor(const LightView& light, const Eigen::Vector3f& from_light) {
  if (!light.spot) return 1.0f;
  const float c = from_light.dot(light.direction);
  if (c <= light.outer) return 0.0f;
  if (c >= light.inner || light.inner <= light.outer) return 1.0f;
  const float s = (c - light.outer) / (light.inner - light.outer);
  return s * s * (3.0f - 2.0f * s);
}

// What one light does at one surface point, before its shadow rays are answered.
struct LightTerm {
  bool lit = false;  // faces the light and lies in its cone: a term, and shadow rays
  float lambert = 0.0f, spot = 0.0f;
  Eigen::Vector3f to_light;
  // A soft shadow's disc, facing the point: two unit vectors across it.
  Eigen::Vector3f a, b;
};

// A pixel with a surface, in the tile being shaded.
struct SurfacePixel {
  int x, y;
  fs_u32 pixel;  // the jitter's key: y * width + x
  const Material* material;
  Eigen::Vector3f point, normal, geometric, origin;
};

// Shades the pixels of one tile in three passes: each light's term at each surface
// pixel; every shadow ray of the tile, as rtcOccluded16 packets; the colours, handed to
// the caller (linear radiance or sRGB bytes: no float image in between). The rays
// go light by light and sample by sample, each pass over the pixels in 4x4 blocks, so
// that the rays of a packet start close together and end close together (the same
// light, the same sector of its disc): Embree traces such packets fastest.
class TileShader {
 public:
  TileShader(const RenderScene& scene, const RaycastImages& images, const ShadingOptions& options,
             const std::vector<LightView>& lights)
      : scene_(scene), images_(images), options_(options), lights_(lights),
        shadows_(scene.embree_scene()) {
    // One allocation each per tile, not one per doubling.
    pixels_.reserve(render_detail::kTileSize * render_detail::kTileSize);
    terms_.reserve(pixels_.capacity() * lights.size());
  }

  // Calls write(x, y, colour) with the linear RGB colour of each pixel of the tile that
  // has a surface.
  template <class Write>
  void shade(int x0, int y0, int x1, int y1, const Write& write) {
    gather(x0, y0, x1, y1);
    if (pixels_.empty()) return;
    weigh_lights();
    cast_shadow_rays();
    for (size_t i = 0; i < pixels_.size(); ++i) write(pixels_[i].x, pixels_[i].y, colour(i));
  }

 private:
  LightTerm& term(size_t pixel, size_t light) { return terms_[pixel * lights_.size() + light]; }
  int slot(size_t pixel, size_t light) const { return int(pixel * lights_.size() + light); }

  // The tile's pixels with a surface, in 4x4 blocks (each block row by row).
  void gather(int x0, int y0, int x1, int y1) {
    pixels_.clear();
    const int width = images_.depth.cols;
    for (int by = y0; by < y1; by += 4) {
      for (int bx = x0; bx < x1; bx += 4) {
        for (int y = by; y < std::min(by + 4, y1); ++y) {
          for (int x = bx; x < std::min(bx + 4, x1); ++x) {
            const int id = images_.instance.at<std::int32_t>(y, x);
            if (id < 0) continue;
            const cv::Vec3f& p = images_.point.at<cv::Vec3f>(y, x);
            const cv::Vec3f& ns = images_.normal.at<cv::Vec3f>(y, x);
            const cv::Vec3f& ng = images_.geometric_normal.at<cv::Vec3f>(y, x);
            SurfacePixel s;
            s.x = x;
            s.y = y;
            s.pixel = fs_u32(y) * fs_u32(width) + fs_u32(x);
            s.material = &scene_.instance(id).material;
            s.point = Eigen::Vector3f(p[0], p[1], p[2]);
            s.normal = Eigen::Vector3f(ns[0], ns[1], ns[2]);
            s.geometric = Eigen::Vector3f(ng[0], ng[1], ng[2]);
            s.origin = shadow_origin(s.point, s.geometric);
            pixels_.push_back(s);
          }
        }
      }
    }
  }

  void weigh_lights() {
    terms_.assign(pixels_.size() * lights_.size(), LightTerm{});
    for (size_t i = 0; i < pixels_.size(); ++i) {
      const SurfacePixel& s = pixels_[i];
      for (size_t l = 0; l < lights_.size(); ++l) {
        const Light& light = *lights_[l].light;
        LightTerm& t = term(i, l);
        t.to_light = (light.position - s.point).normalized();
        t.lambert = s.normal.dot(t.to_light);
        // A light behind the triangle itself lights nothing there, whatever the
        // interpolated normal says; nor does a spot outside its cone. Neither needs a
        // shadow ray.
        if (t.lambert <= 0.0f || s.geometric.dot(t.to_light) <= 0.0f) continue;
        t.spot = spot_factor(lights_[l], -t.to_light);
        if (t.spot <= 0.0f) continue;
        t.lit = true;
        if (lights_[l].casts_shadows && light.radius > 0.0f) {
          const Eigen::Vector3f w = (light.position - s.origin).normalized();
          const Eigen::Vector3f helper =
              std::abs(w.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
          t.a = w.cross(helper).normalized();
          t.b = w.cross(t.a);
        }
      }
    }
  }

  // Hard shadows: one ray to the light's centre. Soft ones: ShadingOptions::shadow_samples
  // rays to jittered points of the disc, stratified in angle so that few of them already
  // cover it; the jitter is keyed by (seed, pixel, light, sample), never by order.
  void cast_shadow_rays() {
    shadows_.reset(int(pixels_.size() * lights_.size()));
    for (size_t l = 0; l < lights_.size(); ++l) {
      if (!lights_[l].casts_shadows) continue;
      const Light& light = *lights_[l].light;
      const int samples = light.radius > 0.0f ? options_.shadow_samples : 1;
      for (int k = 0; k < samples; ++k) {
        for (size_t i = 0; i < pixels_.size(); ++i) {
          const LightTerm& t = term(i, l);
          if (!t.lit) continue;
          const SurfacePixel& s = pixels_[i];
          if (light.radius <= 0.0f) {
            shadows_.add(s.origin, light.position, slot(i, l));
            continue;
          }
          const auto jitter = shadow_jitter(options_.seed, s.pixel, fs_u32(l), fs_u32(k));
          const float r = light.radius * std::sqrt(jitter[0]);
          const float phi = 2.0f * kPi * (float(k) + jitter[1]) / float(options_.shadow_samples);
          const Eigen::Vector3f target =
              light.position + r * (std::cos(phi) * t.a + std::sin(phi) * t.b);
          shadows_.add(s.origin, target, slot(i, l));
        }
      }
    }
    shadows_.flush();
  }

  // Fraction of the light that reaches pixel i: 1 or 0 for a point light, the share of
  // unblocked rays for a disc; 1 without shadows.
  float visibility(size_t i, size_t l) const {
    if (!lights_[l].casts_shadows) return 1.0f;
    const int unblocked = shadows_.unblocked(slot(i, l));
    if (lights_[l].light->radius <= 0.0f) return unblocked > 0 ? 1.0f : 0.0f;
    return float(unblocked) / float(options_.shadow_samples);
  }

  // Ambient plus, per light, Lambert and the highlight, times the light's visibility
  // and cone.
  Eigen::Vector3f colour(size_t i) {
    const SurfacePixel& s = pixels_[i];
    const Material& material = *s.material;
    const Eigen::Vector3f to_eye = -s.point.normalized();
    Eigen::Vector3f colour = options_.ambient * material.albedo;
    for (size_t l = 0; l < lights_.size(); ++l) {
      const LightTerm& t = term(i, l);
      if (!t.lit) continue;
      const float visible = visibility(i, l);
      if (visible <= 0.0f) continue;
      const Eigen::Vector3f half = (t.to_light + to_eye).normalized();
      const float highlight =
          material.specular * std::pow(std::max(s.normal.dot(half), 0.0f), material.shininess);
      colour += (visible * t.spot) *
                lights_[l].light->intensity.cwiseProduct(t.lambert * material.albedo +
                                                         Eigen::Vector3f::Constant(highlight));
    }
    return colour;
  }

  const RenderScene& scene_;
  const RaycastImages& images_;
  const ShadingOptions& options_;
  const std::vector<LightView>& lights_;
  ShadowPackets shadows_;
  std::vector<SurfacePixel> pixels_;
  std::vector<LightTerm> terms_;  // pixel-major: terms_[pixel * lights + light]
};

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

namespace {

// Runs `write(x, y, colour)` for every pixel with a surface, tile by tile on the
// options' threads.
template <class Write>
void shade_pixels(const RenderScene& scene, const RaycastImages& images,
                  const ShadingOptions& options, const Write& write) {
  options.check();
  if (!scene.committed()) {
    throw std::logic_error("shading needs RenderScene::commit() after the last change");
  }
  std::vector<Light> lights = options.lights;
  const size_t scene_lights = lights.size();
  if (options.camera_light) {
    Light camera;
    camera.position = Eigen::Vector3f::Zero();
    camera.intensity = options.camera_light_intensity;
    lights.push_back(camera);
  }
  std::vector<LightView> views;
  for (size_t l = 0; l < lights.size(); ++l) {
    views.push_back(view_light(lights[l], options.shadows && l < scene_lights));
  }
  render_detail::for_each_tile(
      cv::Rect(0, 0, images.depth.cols, images.depth.rows), options.threads,
      [&](int x0, int y0, int x1, int y1) {
        TileShader(scene, images, options, views).shade(x0, y0, x1, y1, write);
      });
}

}  // namespace

cv::Mat shade_linear(const RenderScene& scene, const RaycastImages& images,
                     const ShadingOptions& options) {
  cv::Mat radiance = cv::Mat::zeros(images.depth.size(), CV_32FC3);
  shade_pixels(scene, images, options, [&](int x, int y, const Eigen::Vector3f& colour) {
    radiance.at<cv::Vec3f>(y, x) = {colour.x(), colour.y(), colour.z()};
  });
  return radiance;
}

cv::Mat shade(const RenderScene& scene, const RaycastImages& images,
              const ShadingOptions& options) {
  static const SrgbTable srgb;
  cv::Mat rgb(images.depth.size(), CV_8UC3, cv::Scalar(options.background[0],
                                                      options.background[1],
                                                      options.background[2]));
  shade_pixels(scene, images, options, [&](int x, int y, const Eigen::Vector3f& colour) {
    rgb.at<cv::Vec3b>(y, x) = {srgb(colour.x()), srgb(colour.y()), srgb(colour.z())};
  });
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

#pragma once
// Colour images of a ray-cast scene: Lambert diffuse plus a Blinn-Phong highlight under
// one to three point or spot lights with hard or soft shadows, an ambient term, and an
// optional light at the camera. Enough for texture-less grey parts, whose look is all
// in shading, edges and shadows; not a path tracer (no inter-reflection).
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "host/render/raycaster.h"

namespace flexsight {

struct Light {
  // Position in the camera frame (mm; y points down, so a light above the scene has a
  // negative y).
  Eigen::Vector3f position{-300.0f, -800.0f, 200.0f};
  // Linear RGB intensity. No fall-off with distance: the parts of a scene lie within a
  // few centimetres of each other at about a metre, where 1 / d^2 would change the
  // light by a few per cent only, and a constant keeps the lights easy to balance.
  Eigen::Vector3f intensity{0.8f, 0.8f, 0.8f};
  // Radius in mm of the light's disc: 0 casts hard shadows; a larger disc casts soft
  // ones, from ShadingOptions::shadow_samples points on it.
  float radius = 0.0f;
  // A spot light lights the cone of half-angle cone_degrees around `direction`, fading
  // to nothing over its outer falloff_degrees; cone_degrees 180 is a point light.
  Eigen::Vector3f direction{0.0f, 0.0f, 1.0f};
  float cone_degrees = 180.0f;
  float falloff_degrees = 5.0f;
};

struct ShadingOptions {
  // Up to three lights in the scene.
  std::vector<Light> lights{Light{}};
  // A light at the camera centre (a ring light around the lens), with no shadows: every
  // point the camera sees, it also lights.
  bool camera_light = false;
  Eigen::Vector3f camera_light_intensity{0.4f, 0.4f, 0.4f};
  // Light that reaches everything, times the albedo: stands in for the inter-reflections
  // that keep real shadows from being black.
  float ambient = 0.15f;
  // Shadow rays towards each light (rtcOccluded16 packets, shadow_packets.h); without
  // them every surface facing a light is lit.
  bool shadows = true;
  // Shadow rays per pixel towards a light with a radius, at jittered points of its disc.
  int shadow_samples = 8;
  // Key of the jitter: the same seed gives the same bytes, whatever the thread count.
  std::uint32_t seed = 1;
  // RGB of the pixels where no surface is.
  cv::Vec3b background{0, 0, 0};
  // OpenMP threads over image tiles; 0 takes OpenMP's default.
  int threads = 0;
  // Throws InputError ("lighting: ...") for no light or more than three, a negative
  // intensity, radius or ambient, a cone outside (0, 180] degrees, or a sample count
  // outside 1..256.
  void check() const;
};

// Linear RGB radiance (CV_32FC3) per pixel; 0 where no surface.
cv::Mat shade_linear(const RenderScene& scene, const RaycastImages& images,
                     const ShadingOptions& options = {});

// The picture: shade_linear clipped to [0, 1], sRGB-encoded, 8-bit RGB (CV_8UC3), the
// background where no surface.
cv::Mat shade(const RenderScene& scene, const RaycastImages& images,
              const ShadingOptions& options = {});

// A grey albedo with a slight tint, different per instance and the same for the same
// (seed, instance): grey levels 0.45-0.75, each channel within 4 % of the grey.
Eigen::Vector3f tinted_grey(std::uint32_t seed, int instance);

}  // namespace flexsight

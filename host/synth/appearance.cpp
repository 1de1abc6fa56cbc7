#include "host/synth/appearance.h"

#include <algorithm>
#include <cmath>

namespace flexsight {

using synth_detail::SynthRandom;

Material draw_material(const FullSyntheticSettings& settings, SynthRandom& random) {
  Material material;
  const double grey = random.uniform(settings.min_grey, settings.max_grey);
  for (int c = 0; c < 3; ++c) {
    const double tint = random.uniform(-settings.max_tint, settings.max_tint);
    material.albedo[c] = static_cast<float>(std::clamp(grey * (1.0 + tint), 0.0, 1.0));
  }
  material.specular =
      static_cast<float>(random.uniform(settings.min_specular, settings.max_specular));
  material.shininess =
      static_cast<float>(random.log_uniform(settings.min_shininess, settings.max_shininess));
  return material;
}

ShadingOptions draw_lighting(const FullSyntheticSettings& settings, const Eigen::Vector3d& centre,
                             double reach, const Eigen::Matrix3d& camera_rotation,
                             std::uint32_t seed, std::int64_t image_index) {
  SynthRandom random(seed, image_index, synth_detail::kStreamAppearance);
  // Drawn in the unrotated camera's frame.
  const Eigen::Vector3d centre0 = camera_rotation.transpose() * centre;
  const double depth = std::max(centre0.z(), 1.0);
  ShadingOptions options;
  options.lights.clear();
  const int count = random.integer(settings.min_lights, settings.max_lights);
  for (int i = 0; i < count; ++i) {
    // Direction from the parts towards the light: within 70 degrees of the direction
    // back to the camera, any azimuth (above, beside, below: a training image has no
    // "up"); beyond every part by 0.5 to 2 times the parts' distance from the camera,
    // so that no light sits among the parts and its direction changes little across
    // them, as with lamps over a work cell.
    const double polar = random.uniform(0.0, 70.0) * M_PI / 180.0;
    const double azimuth = random.uniform(0.0, 2.0 * M_PI);
    const Eigen::Vector3d towards(std::sin(polar) * std::cos(azimuth),
                                  std::sin(polar) * std::sin(azimuth), -std::cos(polar));
    const double distance = reach + depth * random.uniform(0.5, 2.0);
    const Eigen::Vector3d position = centre0 + distance * towards;
    // Brightness shared out so that three lights do not wash the parts out; a slight
    // warm or cool colour.
    const double strength = random.uniform(0.5, 1.2) / std::sqrt(double(count));
    const double warmth = random.uniform(-0.1, 0.1);
    Light light;
    light.position = (camera_rotation * position).cast<float>();
    light.intensity =
        Eigen::Vector3d(strength * (1.0 + warmth), strength, strength * (1.0 - warmth))
            .cast<float>();
    const bool soft = random.chance(settings.soft_shadow_probability);
    const double radius_fraction = random.uniform(0.02, 0.1);
    light.radius = soft ? static_cast<float>(distance * radius_fraction) : 0.0f;
    const bool spot = random.chance(settings.spot_probability);
    // A spot aims near the parts' centre with a cone of 10 to 30 degrees: at the drawn
    // distances it lights part of the picture, and its edge falls across some parts.
    const Eigen::Vector3d aim = centre0 + depth * Eigen::Vector3d(random.uniform(-0.3, 0.3),
                                                                  random.uniform(-0.3, 0.3), 0.0);
    const double cone = random.uniform(10.0, 30.0);
    const double falloff = random.uniform(2.0, 10.0);
    if (spot) {
      light.direction = (camera_rotation * (aim - position).normalized()).cast<float>();
      light.cone_degrees = static_cast<float>(cone);
      light.falloff_degrees = static_cast<float>(falloff);
    }
    options.lights.push_back(light);
  }
  options.camera_light = random.chance(settings.camera_light_probability);
  const float camera_light = static_cast<float>(random.uniform(0.1, 0.4));
  options.camera_light_intensity = Eigen::Vector3f::Constant(camera_light);
  options.ambient = static_cast<float>(random.uniform(settings.min_ambient, settings.max_ambient));
  options.shadows = true;
  options.shadow_samples = settings.shadow_samples;
  options.seed = static_cast<std::uint32_t>(random.next_u64());
  options.threads = 1;
  return options;
}

}  // namespace flexsight

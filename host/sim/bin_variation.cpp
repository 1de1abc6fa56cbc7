#include "host/sim/bin_variation.h"

#include <cmath>
#include <sstream>

#include "host/io/input_error.h"
#include "host/synth/synth_random.h"

namespace flexsight {
namespace {

using synth_detail::SynthRandom;

// One random stream per aspect, apart from bin_scene.cpp's (0xB1..0xB4, 0xC3 the shading
// seed, 0xB4 + 0x100 per image for the noise).
enum VaryStream : std::uint32_t {
  kStreamMaterial = 0xD1,
  kStreamLights = 0xD2,
  kStreamProjector = 0xD3,
  kStreamCamera = 0xD4,
  kStreamOptics = 0xD5,
};

const struct {
  const char* name;
  unsigned bit;
} kAspects[] = {{"material", kVaryMaterial}, {"lights", kVaryLights}, {"projector", kVaryProjector},
                {"camera", kVaryCamera},     {"optics", kVaryOptics}};

// Matte grey plastic (the unvaried bins' parts, a broad weak highlight) or bare metal
// (dark diffuse, a strong narrow highlight that saturates).
Material draw_part_material(SynthRandom& random, bool metal) {
  Material material;
  const float grey = float(metal ? random.uniform(0.04, 0.15) : random.uniform(0.12, 0.75));
  material.albedo = Eigen::Vector3f::Constant(grey);
  for (int c = 0; c < 3; ++c) material.albedo[c] *= float(random.uniform(0.96, 1.04));
  material.specular = float(metal ? random.uniform(1.0, 4.0) : random.uniform(0.05, 0.4));
  material.shininess = float(metal ? random.log_uniform(60.0, 500.0) : random.log_uniform(10.0, 60.0));
  return material;
}

void draw_materials(BinVariation& v, std::uint32_t seed, std::int64_t index, int part_count) {
  SynthRandom random(seed, index, kStreamMaterial);
  v.metal_share = random.uniform();
  v.bin_material.albedo = Eigen::Vector3f::Constant(float(random.uniform(0.25, 0.6)));
  v.bin_material.specular = float(random.uniform(0.02, 0.3));
  for (int i = 0; i < part_count; ++i) {
    const bool metal = random.chance(v.metal_share);
    v.part_is_metal.push_back(metal);
    v.part_materials.push_back(draw_part_material(random, metal));
  }
}

// 1 to 3 ceiling lights anywhere over a 3 x 2.4 m patch of ceiling, warm (halogen) to
// cool (LED daylight), small to broad.
void draw_lights(BinVariation& v, double room_light, double ceiling, std::uint32_t seed, std::int64_t index) {
  SynthRandom random(seed, index, kStreamLights);
  const int count = random.integer(1, 3);
  const Eigen::Vector3f warm(1.0f, 0.82f, 0.64f), cool(0.86f, 0.93f, 1.0f);
  for (int i = 0; i < count; ++i) {
    RoomLamp lamp;
    lamp.position = {random.uniform(-1500.0, 1500.0), random.uniform(-1200.0, 1200.0),
                     ceiling + random.uniform(-500.0, 700.0)};
    const float t = float(random.uniform());
    const float strength = float(room_light * random.uniform(0.3, 1.3));
    lamp.intensity = strength * ((1.0f - t) * warm + t * cool);
    lamp.radius_mm = float(random.uniform(30.0, 300.0));
    v.lamps.push_back(lamp);
  }
  v.ambient = random.uniform(0.04, 0.2);
}

void draw_projector(BinVariation& v, const ProjectorSettings& projector, std::uint32_t seed,
                    std::int64_t index) {
  SynthRandom random(seed, index, kStreamProjector);
  v.projector_power = projector.power * random.uniform(0.5, 1.5);
  v.dot_sigma_degrees = projector.dot_sigma_degrees * random.uniform(0.75, 1.4);
  v.dot_blur_degrees = random.uniform(0.0, 0.03);
}

// Noise level u in [LO, HI] of --noise-level: full well 20,000 electrons (a large pixel,
// bright scene) down to 1,500 (a small pixel or short exposure), read noise 2 to 12 e-.
void draw_cameras(BinVariation& v, const BinSimSettings& settings, std::uint32_t seed, std::int64_t index) {
  SynthRandom random(seed, index, kStreamCamera);
  v.noise_level = random.uniform(settings.noise_level_min, settings.noise_level_max);
  const double full_well = 20000.0 * std::pow(1500.0 / 20000.0, v.noise_level);
  const double read = 2.0 + 10.0 * v.noise_level;
  for (CameraLook& camera : v.cameras) {
    camera.exposure = random.uniform(0.75, 1.3);
    camera.gain = random.log_uniform(0.8, 1.25);
    camera.full_well_e = full_well;
    camera.read_noise_e = read;
  }
}

void draw_optics(BinVariation& v, std::uint32_t seed, std::int64_t index) {
  SynthRandom random(seed, index, kStreamOptics);
  for (CameraLook& camera : v.cameras) {
    camera.vignetting = random.uniform(0.0, 0.35);
    camera.defocus_px = random.uniform(0.0, 0.8);
  }
}

nlohmann::json material_json(const Material& m) {
  return {{"albedo", {m.albedo.x(), m.albedo.y(), m.albedo.z()}},
          {"specular", m.specular},
          {"shininess", m.shininess}};
}

}  // namespace

unsigned parse_vary_list(const std::string& text) {
  if (text == "all") return kVaryAll;
  if (text == "none") return 0;
  unsigned aspects = 0;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    unsigned bit = 0;
    for (const auto& aspect : kAspects) {
      if (item == aspect.name) bit = aspect.bit;
    }
    if (bit == 0) {
      throw InputError("option --vary", "unknown aspect '" + item +
                                            "' (expected all, none or a list of material, lights, "
                                            "projector, camera, optics)");
    }
    aspects |= bit;
  }
  if (aspects == 0 || text.back() == ',') throw InputError("option --vary", "empty list '" + text + "'");
  return aspects;
}

std::string vary_list_text(unsigned aspects) {
  std::string text;
  for (const auto& aspect : kAspects) {
    if (aspects & aspect.bit) text += (text.empty() ? "" : ",") + std::string(aspect.name);
  }
  return text.empty() ? "none" : text;
}

std::vector<RoomLamp> fixed_room_lamps(double room_light, double ceiling) {
  std::vector<RoomLamp> lamps;
  const struct {
    Eigen::Vector3d position;
    double share;
  } fixed[] = {{{-700.0, 500.0, ceiling}, 1.0}, {{900.0, -700.0, ceiling}, 0.4}};
  for (const auto& f : fixed) {
    lamps.push_back({f.position, Eigen::Vector3f::Constant(float(room_light * f.share)), 150.0f});
  }
  return lamps;
}

BinVariation draw_bin_variation(const BinSimSettings& settings, double ceiling, std::uint32_t seed,
                                std::int64_t index, int part_count) {
  BinVariation v;
  v.aspects = settings.vary;
  v.lamps = fixed_room_lamps(settings.room_light, ceiling);
  v.ambient = settings.ambient;
  v.projector_power = settings.projector.power;
  v.dot_sigma_degrees = settings.projector.dot_sigma_degrees;
  if (v.aspects & kVaryMaterial) draw_materials(v, seed, index, part_count);
  if (v.aspects & kVaryLights) {
    v.lamps.clear();
    draw_lights(v, settings.room_light, ceiling, seed, index);
  }
  if (v.aspects & kVaryProjector) draw_projector(v, settings.projector, seed, index);
  if (v.aspects & kVaryCamera) draw_cameras(v, settings, seed, index);
  if (v.aspects & kVaryOptics) draw_optics(v, seed, index);
  return v;
}

nlohmann::json variation_json(const BinVariation& v) {
  nlohmann::json info = {{"aspects", vary_list_text(v.aspects)}};
  if (v.aspects & kVaryMaterial) {
    nlohmann::json parts = nlohmann::json::array();
    for (std::size_t i = 0; i < v.part_materials.size(); ++i) {
      nlohmann::json part = material_json(v.part_materials[i]);
      part["metal"] = bool(v.part_is_metal[i]);
      parts.push_back(part);
    }
    info["material"] = {{"metal_share", v.metal_share}, {"bin", material_json(v.bin_material)}, {"parts", parts}};
  }
  if (v.aspects & kVaryLights) {
    nlohmann::json lamps = nlohmann::json::array();
    for (const RoomLamp& lamp : v.lamps) {
      lamps.push_back({{"position_mm", {lamp.position.x(), lamp.position.y(), lamp.position.z()}},
                       {"intensity_rgb", {lamp.intensity.x(), lamp.intensity.y(), lamp.intensity.z()}},
                       {"radius_mm", lamp.radius_mm}});
    }
    info["lights"] = {{"lamps", lamps}, {"ambient", v.ambient}};
  }
  if (v.aspects & kVaryProjector) {
    info["projector"] = {{"power", v.projector_power},
                         {"dot_sigma_degrees", v.dot_sigma_degrees},
                         {"dot_blur_degrees", v.dot_blur_degrees}};
  }
  if (v.aspects & (kVaryCamera | kVaryOptics)) {
    nlohmann::json cameras = nlohmann::json::array();
    for (const CameraLook& c : v.cameras) {
      nlohmann::json camera;
      if (v.aspects & kVaryCamera) {
        camera.update({{"exposure", c.exposure}, {"gain", c.gain}, {"full_well_e", c.full_well_e},
                       {"read_noise_e", c.read_noise_e}});
      }
      if (v.aspects & kVaryOptics) camera.update({{"vignetting", c.vignetting}, {"defocus_px", c.defocus_px}});
      cameras.push_back(camera);
    }
    info["cameras"] = cameras;  // left, right
    if (v.aspects & kVaryCamera) info["noise_level"] = v.noise_level;
  }
  return info;
}

}  // namespace flexsight

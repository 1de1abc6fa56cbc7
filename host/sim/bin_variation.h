#pragma once
// Per-bin randomisation of how a bin looks (`synth bin --vary`): the parts' materials,
// the room lights, the projector, each camera's exposure, gain, noise and optics. Every
// value is drawn from (seed, bin index) and one random stream per aspect, so turning one
// aspect on or off leaves the others' values as they were; all of them are recorded in
// the bin's sim_info.json (variation_json). The ranges and why: docs/sim.md, "Varied
// bins".
#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "host/render/raycaster.h"
#include "host/sim/bin_settings.h"

namespace flexsight {

// A room light in the bin frame (mm, z up).
struct RoomLamp {
  Eigen::Vector3d position;
  Eigen::Vector3f intensity;  // linear RGB
  float radius_mm = 150.0f;
};

// What one camera does to the radiance that reaches it (sensor_model.h).
struct CameraLook {
  // Relative exposure time and analogue gain: the picture is their product times the
  // radiance; they differ in noise (exposure collects more photons, gain amplifies them).
  double exposure = 1.0, gain = 1.0;
  // Electrons at linear value 1 (shot noise: sqrt of the electrons) and read noise in
  // electrons; 0 full well: no sensor model, the fixed Gaussian `--noise` instead.
  double full_well_e = 0.0, read_noise_e = 0.0;
  // Relative fall-off at the image corners: 1 - vignetting (r / r_corner)^2.
  double vignetting = 0.0;
  // Gaussian blur of the radiance, pixels (slight defocus).
  double defocus_px = 0.0;
};

struct BinVariation {
  unsigned aspects = 0;  // BinVaryAspect bits
  // kVaryMaterial: the share of metal parts in this bin, each part's material, the bin's.
  double metal_share = 0.0;
  std::vector<Material> part_materials;
  std::vector<bool> part_is_metal;
  Material bin_material;
  // kVaryLights (else the two fixed ceiling lights).
  std::vector<RoomLamp> lamps;
  double ambient = 0.0;
  // kVaryProjector.
  double projector_power = 0.0, dot_sigma_degrees = 0.0, dot_blur_degrees = 0.0;
  // kVaryCamera / kVaryOptics: left, right.
  double noise_level = 0.0;
  CameraLook cameras[2];
};

// "all", "none" or a comma-separated list of material, lights, projector, camera,
// optics; InputError naming --vary for an unknown or empty entry.
unsigned parse_vary_list(const std::string& text);
std::string vary_list_text(unsigned aspects);

// The two fixed ceiling lights of an unvaried bin: up and to the side of the cameras,
// and a weaker one opposite. `ceiling` is the lights' height in the bin frame.
std::vector<RoomLamp> fixed_room_lamps(double room_light, double ceiling);

// The values of bin `index` for the aspects in settings.vary; the aspects not varied keep
// the settings' values. `part_count`: the parts at rest (one material each).
BinVariation draw_bin_variation(const BinSimSettings& settings, double ceiling, std::uint32_t seed,
                                std::int64_t index, int part_count);

// Everything drawn, for sim_info.json.
nlohmann::json variation_json(const BinVariation& variation);

}  // namespace flexsight

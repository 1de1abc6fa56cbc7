#include "host/cli/synth_settings_options.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "host/cli/arguments.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

// The options of the background crop and the camera effects, which the full and the
// semi-synthetic settings share (BackgroundEffects).
std::vector<SettingOption> background_effect_options(BackgroundEffects& s) {
  return {
      {"min-crop-scale", &s.min_crop_scale, nullptr, "smallest background crop"},
      {"crop-aspect-change", &s.max_crop_aspect_change, nullptr, "log aspect change of the crop"},
      {"background-flip", &s.background_flip_probability, nullptr, "chance the background is mirrored"},
      {"blur-probability", &s.blur_probability, nullptr, "chance of a blur"},
      {"max-blur", &s.max_blur_sigma, nullptr, "largest blur sigma, pixels"},
      {"max-noise", &s.max_noise_sigma, nullptr, "largest noise sigma, grey levels"},
  };
}

void append(std::vector<SettingOption>& options, const std::vector<SettingOption>& more) {
  options.insert(options.end(), more.begin(), more.end());
}

}  // namespace

std::vector<SettingOption> full_synthetic_setting_options(FullSyntheticSettings& s) {
  std::vector<SettingOption> options = {
      {"fov", &s.horizontal_fov_degrees, nullptr, "horizontal field of view, degrees"},
      {"min-parts", nullptr, &s.min_parts, "fewest parts per image"},
      {"max-parts", nullptr, &s.max_parts, "most parts per image"},
      {"min-size", &s.min_part_size, nullptr, "smallest part diameter, fraction of the width"},
      {"max-size", &s.max_part_size, nullptr, "largest part diameter, fraction of the width"},
      {"min-visible", &s.min_visible_fraction, nullptr, "least visible fraction of a part"},
      {"pose-attempts", nullptr, &s.pose_attempts, "poses tried per part under the cap"},
      {"min-grey", &s.min_grey, nullptr, "darkest albedo (linear)"},
      {"max-grey", &s.max_grey, nullptr, "brightest albedo (linear)"},
      {"max-tint", &s.max_tint, nullptr, "largest colour tint of the albedo"},
      {"min-specular", &s.min_specular, nullptr, "weakest highlight"},
      {"max-specular", &s.max_specular, nullptr, "strongest highlight"},
      {"min-shininess", &s.min_shininess, nullptr, "broadest highlight (exponent)"},
      {"max-shininess", &s.max_shininess, nullptr, "tightest highlight (exponent)"},
      {"min-lights", nullptr, &s.min_lights, "fewest lights"},
      {"max-lights", nullptr, &s.max_lights, "most lights (up to 3)"},
      {"spot-probability", &s.spot_probability, nullptr, "chance a light is a spot"},
      {"soft-shadows", &s.soft_shadow_probability, nullptr, "chance a light casts soft shadows"},
      {"shadow-samples", nullptr, &s.shadow_samples, "shadow rays per pixel, soft lights"},
      {"camera-light", &s.camera_light_probability, nullptr, "chance of a light at the camera"},
      {"min-ambient", &s.min_ambient, nullptr, "least ambient light"},
      {"max-ambient", &s.max_ambient, nullptr, "most ambient light"},
  };
  append(options, background_effect_options(s));
  append(options, {
      {"hflip", &s.horizontal_flip_probability, nullptr, "chance of a horizontal flip"},
      {"vflip", &s.vertical_flip_probability, nullptr, "chance of a vertical flip"},
      {"max-rotation", &s.max_rotation_degrees, nullptr, "largest in-plane rotation, degrees"},
      {"depth-noise", &s.depth_noise.disparity_sigma, nullptr, "stored depth: disparity noise, pixels"},
      {"depth-baseline", &s.depth_noise.baseline_mm, nullptr, "stored depth: stereo baseline, mm"},
      {"depth-dropout", nullptr, &s.depth_noise.edge_dropout, "stored depth: no depth this near steps"},
  });
  return options;
}

std::vector<SettingOption> semi_synthetic_setting_options(SemiSyntheticSettings& s) {
  std::vector<SettingOption> options = {
      {"min-parts", nullptr, &s.min_parts, "fewest parts per image"},
      {"max-parts", nullptr, &s.max_parts, "most parts per image"},
      {"min-size", &s.min_part_size, nullptr, "smallest patch diagonal, fraction of the width"},
      {"max-size", &s.max_part_size, nullptr, "largest patch diagonal, fraction of the width"},
      {"max-rotation", &s.max_rotation_degrees, nullptr, "largest turn of a patch, degrees"},
      {"mirror", &s.mirror_probability, nullptr, "chance a patch is mirrored"},
      {"max-brightness", &s.max_brightness, nullptr, "largest brightness change, grey levels"},
      {"min-contrast", &s.min_contrast, nullptr, "smallest contrast gain"},
      {"max-contrast", &s.max_contrast, nullptr, "largest contrast gain"},
      {"min-visible", &s.min_visible_fraction, nullptr, "least visible fraction of a part"},
      {"pose-attempts", nullptr, &s.pose_attempts, "placements tried per part under the cap"},
  };
  append(options, background_effect_options(s));
  return options;
}

void take_settings_options(std::vector<std::string>& args, const std::vector<SettingOption>& options) {
  for (const SettingOption& option : options) {
    const std::string flag = "--" + option.name;
    const std::string text = take_option(args, flag);
    if (text.empty()) continue;
    std::size_t used = 0;
    double value = NAN;
    try {
      value = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size() || !std::isfinite(value)) {
      throw InputError("option " + flag, "expected a number, got '" + text + "'");
    }
    if (option.real) {
      *option.real = value;
    } else {
      if (value != std::floor(value) || std::fabs(value) > 1e9) {
        throw InputError("option " + flag, "expected a whole number, got '" + text + "'");
      }
      *option.integer = static_cast<int>(value);
    }
  }
}

void take_size_option(std::vector<std::string>& args, int& width, int& height) {
  const std::string text = take_option(args, "--size");
  if (text.empty()) return;
  const std::size_t x = text.find('x');
  std::size_t used_w = 0, used_h = 0;
  long w = 0, h = 0;
  try {
    if (x != std::string::npos) {
      w = std::stol(text.substr(0, x), &used_w);
      h = std::stol(text.substr(x + 1), &used_h);
    }
  } catch (const std::exception&) {
    used_w = 0;
  }
  if (x == std::string::npos || used_w != x || used_h != text.size() - x - 1 || used_w == 0 ||
      w < 8 || h < 8 || w > 16384 || h > 16384) {
    throw InputError("option --size", "expected WxH with 8 <= W, H <= 16384 (e.g. 300x300), got '" +
                                          text + "'");
  }
  width = static_cast<int>(w);
  height = static_cast<int>(h);
}

std::string settings_options_help(const std::vector<SettingOption>& options) {
  std::ostringstream text;
  for (const SettingOption& option : options) {
    std::ostringstream value;
    if (option.real) {
      value << *option.real;
    } else {
      value << *option.integer;
    }
    text << "  --" << std::left << std::setw(20) << (option.name + " " + value.str()) << "  "
         << option.help << "\n";
  }
  return text.str();
}

nlohmann::json settings_json(const std::vector<SettingOption>& options, int width, int height) {
  nlohmann::json json = {{"width", width}, {"height", height}};
  for (const SettingOption& option : options) {
    if (option.real) {
      json[option.name] = *option.real;
    } else {
      json[option.name] = *option.integer;
    }
  }
  return json;
}

}  // namespace flexsight

// The generator's settings: the defaults pass, the camera they give, and every
// impossible value an InputError naming its option.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "host/io/input_error.h"
#include "host/synth/full_synthetic_settings.h"

using namespace flexsight;

TEST(SynthSettings, DefaultsPassAndGiveACentredSquarePixelCamera) {
  const FullSyntheticSettings settings;
  EXPECT_NO_THROW(settings.check());
  const PinholeCamera camera = settings.camera();
  EXPECT_EQ(camera.width, 300);
  EXPECT_EQ(camera.fx, camera.fy);
  EXPECT_EQ(camera.cx, 149.5);
  EXPECT_EQ(camera.cy, 149.5);
  // 50 degrees across the width.
  EXPECT_NEAR(2.0 * std::atan(150.0 / camera.fx) * 180.0 / M_PI, 50.0, 1e-9);
}

TEST(SynthSettings, ImpossibleValuesNameTheirOption) {
  struct Case {
    const char* option;
    std::function<void(FullSyntheticSettings&)> spoil;
  };
  const Case cases[] = {
      {"width", [](FullSyntheticSettings& s) { s.width = 0; }},
      {"height", [](FullSyntheticSettings& s) { s.height = -3; }},
      {"fov", [](FullSyntheticSettings& s) { s.horizontal_fov_degrees = 180.0; }},
      {"min-parts", [](FullSyntheticSettings& s) { s.min_parts = 0; }},
      {"max-parts", [](FullSyntheticSettings& s) { s.max_parts = 0; }},
      {"min-parts", [](FullSyntheticSettings& s) { s.min_parts = 5, s.max_parts = 4; }},
      {"min-size", [](FullSyntheticSettings& s) { s.min_part_size = 0.0; }},
      {"min-size", [](FullSyntheticSettings& s) { s.min_part_size = -0.1; }},
      {"max-size", [](FullSyntheticSettings& s) { s.max_part_size = 0.0; }},
      {"min-size", [](FullSyntheticSettings& s) { s.min_part_size = 0.5, s.max_part_size = 0.4; }},
      {"min-visible", [](FullSyntheticSettings& s) { s.min_visible_fraction = 1.5; }},
      {"pose-attempts", [](FullSyntheticSettings& s) { s.pose_attempts = 0; }},
      {"min-grey", [](FullSyntheticSettings& s) { s.min_grey = 0.7, s.max_grey = 0.6; }},
      {"max-shininess", [](FullSyntheticSettings& s) { s.max_shininess = NAN; }},
      {"max-lights", [](FullSyntheticSettings& s) { s.max_lights = 4; }},
      {"spot-probability", [](FullSyntheticSettings& s) { s.spot_probability = -0.1; }},
      {"shadow-samples", [](FullSyntheticSettings& s) { s.shadow_samples = 0; }},
      {"min-ambient", [](FullSyntheticSettings& s) { s.min_ambient = 0.5; }},
      {"min-crop-scale", [](FullSyntheticSettings& s) { s.min_crop_scale = 0.0; }},
      {"max-noise", [](FullSyntheticSettings& s) { s.max_noise_sigma = -1.0; }},
      {"hflip", [](FullSyntheticSettings& s) { s.horizontal_flip_probability = 2.0; }},
      {"max-rotation", [](FullSyntheticSettings& s) { s.max_rotation_degrees = -5.0; }},
  };
  for (const Case& c : cases) {
    FullSyntheticSettings settings;
    c.spoil(settings);
    try {
      settings.check();
      ADD_FAILURE() << "no error for --" << c.option;
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(std::string("option --") + c.option + ": ", 0), 0u)
          << e.what();
    }
  }
}

#pragma once
// Everything `flexsight synth bin` can set: the stereo rig, the bin, how many parts, the
// projector, the lights' strength and the camera noise. check() validates them all before
// any work, each failure naming its option.
#include "host/sim/bin_physics.h"
#include "host/sim/dot_projector.h"
#include "host/geometry/stereo_rig.h"

namespace flexsight {

// What a bin's randomisation may change (`--vary`, bin_variation.h); bits of
// BinSimSettings::vary.
enum BinVaryAspect : unsigned {
  kVaryMaterial = 1,   // each part from matte grey plastic to shiny metal; the bin's grey
  kVaryLights = 2,     // number, position, colour, size and strength of the room lights
  kVaryProjector = 4,  // projector power, dot size and blur
  kVaryCamera = 8,     // exposure and gain per camera, shot and read noise
  kVaryOptics = 16,    // vignetting and a slight defocus per camera
  kVaryAll = 31,
};

// How the parts are dropped: one wave of 10..20 (sparse, a layer with a few parts on
// others), or 30..80 in waves of 10 that settle in turn (dense, several layers).
enum class BinPile { sparse, dense };

struct BinSimSettings {
  StereoRigSettings rig;
  BinGeometry bin;
  int min_parts = 10, max_parts = 20;
  ProjectorSettings projector;
  PhysicsSettings physics;
  // Gaussian sensor noise, grey levels (host/synth/camera_effects.h).
  double noise_sigma = 1.5;
  // Room light: strength of the ceiling light and of the ambient term (shading.h).
  double room_light = 0.5, ambient = 0.12;
  BinPile pile = BinPile::sparse;
  // BinVaryAspect bits drawn per bin from (seed, bin index); 0 keeps every bin's look
  // fixed by the options above.
  unsigned vary = 0;
  // Where in the drawn ranges of shot and read noise a bin may fall (0: the least, 1:
  // the most; bin_variation.h); used with kVaryCamera.
  double noise_level_min = 0.0, noise_level_max = 1.0;
  // OpenMP threads for ray casting, shading and the projector (0: all). The bytes do not
  // depend on it.
  int threads = 0;

  // Throws InputError naming the option: make_stereo_rig's checks, a bin whose outer
  // size (walls included) does not fit in the working volume, non-positive bin sizes,
  // parts outside 1..200 or min > max, the projector's checks, a negative noise or light.
  void check() const;
};

// `--pile dense`: 30..80 parts in waves of 10, each wave settled before the next.
void use_dense_pile(BinSimSettings& settings);

}  // namespace flexsight

#pragma once
// Everything `flexsight synth bin` can set: the stereo rig, the bin, how many parts, the
// projector, the lights' strength and the camera noise. check() validates them all before
// any work, each failure naming its option.
#include "host/sim/bin_physics.h"
#include "host/sim/dot_projector.h"
#include "host/geometry/stereo_rig.h"

namespace flexsight {

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
  // OpenMP threads for ray casting, shading and the projector (0: all). The bytes do not
  // depend on it.
  int threads = 0;

  // Throws InputError naming the option: make_stereo_rig's checks, a bin whose outer
  // size (walls included) does not fit in the working volume, non-positive bin sizes,
  // parts outside 1..200 or min > max, the projector's checks, a negative noise or light.
  void check() const;
};

}  // namespace flexsight

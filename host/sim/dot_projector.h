#pragma once
// The active stereo system's dot projector: a fixed pseudo-random pattern of small red
// dots (a laser behind a diffractive element) from the middle of the baseline, which
// gives the matcher texture on the texture-less parts.
//
// Model. The projector looks along the cameras' axis. A dot is a direction, given by its
// two angles (atan(x/z), atan(y/z)) in the projector's frame, drawn uniformly over the
// square field of view from the pattern seed: the pattern never changes between bins, as
// a real projector's does not. Each dot is a Gaussian spot in those angles (sigma in
// degrees). A surface point receives the spots around its direction from the projector,
// times the cosine between its normal and the projector, times its albedo; points the
// projector cannot see (a shadow ray to the projector is blocked: parts cast shadows)
// receive nothing. No fall-off with distance, as the room lights (host/render/shading.h).
//
// A dot is about a pixel wide at the default size, so sampling the spots at pixel centres
// would drop or double dots at random. Instead each pixel gets the spot convolved with
// its own footprint seen from the projector (a box of the pixel's angular width, as a
// Gaussian of the same variance): sigma_eff^2 = sigma^2 + w^2 / 12, peak scaled by
// sigma^2 / sigma_eff^2 so that a dot delivers the same light whatever the resolution.
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "host/render/raycaster.h"

namespace flexsight {

struct ProjectorSettings {
  int dots = 23880;
  double fov_degrees = 35.0;       // square field, both axes
  std::uint32_t pattern_seed = 1;  // the layout of the dots
  double dot_sigma_degrees = 0.035;  // Gaussian radius of a dot (1.5 px at 1280x960)
  // Optical blur of every dot (Gaussian sigma, degrees), added to the pixel's footprint:
  // a dot keeps its light and spreads it (varied bins, bin_variation.h).
  double blur_sigma_degrees = 0.0;
  float power = 2.5f;  // radiance of a dot's centre on a white surface facing it
  Eigen::Vector3f colour{1.0f, 0.08f, 0.04f};  // red laser as an RGB camera sees it
  // Throws InputError naming the option (--dots, --projector-fov, --dot-size) for a
  // count outside 1..10^7, a field outside (0, 170) degrees, a size outside (0, 5].
  void check() const;
};

class DotPattern {
 public:
  explicit DotPattern(const ProjectorSettings& settings);

  const ProjectorSettings& settings() const { return settings_; }
  // The dots' angles (radians): atan(x/z), atan(y/z) in the projector's frame.
  const std::vector<Eigen::Vector2d>& dots() const { return dots_; }
  // The sum of the spots at angles `a` (radians), each widened by `extra_sigma`
  // (radians, the pixel's footprint): 1 at the centre of an isolated dot when
  // extra_sigma is 0.
  double intensity(const Eigen::Vector2d& a, double extra_sigma) const;

 private:
  ProjectorSettings settings_;
  std::vector<Eigen::Vector2d> dots_;
  // Buckets of dots on a square grid over the field, for the neighbours of a direction.
  double half_field_ = 0.0, cell_ = 0.0;
  int cells_ = 0;
  std::vector<std::vector<int>> grid_;
};

// The projector's light at every pixel of `images` (cast from `camera` through `scene`),
// linear RGB CV_32FC3, to add to the shaded radiance. `projector` is its centre in the
// camera's frame (mm). Pixels with no surface or a surface the projector does not see
// stay 0. The same bytes for any thread count.
cv::Mat projector_radiance(const RenderScene& scene, const RaycastImages& images,
                           const PinholeCamera& camera, const Eigen::Vector3d& projector,
                           const DotPattern& pattern, int threads = 0);

}  // namespace flexsight

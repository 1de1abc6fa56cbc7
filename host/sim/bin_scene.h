#pragma once
// One simulated bin: parts dropped by the physics (bin_physics.h), the bin and the table
// under it, seen by both cameras of the stereo rig (stereo_rig.h) under room light, with
// and without the dot projector (dot_projector.h); and what is known exactly about it:
// disparities of both views, the left view's non-occluded pixels, the parts' poses and
// masks.
#include <cstdint>
#include <memory>
#include <vector>

#include "host/dataset/annotated_image.h"
#include "host/sim/bin_settings.h"
#include "host/sim/bin_variation.h"
#include "host/sim/projector_pattern.h"
#include "host/synth/part_library.h"

namespace flexsight {

struct BinPart {
  int part = 0;    // index in the PartLibrary
  int obj_id = 0;
  Pose world;      // model -> bin frame (mm)
  Eigen::Vector3f albedo;
};

struct BinViews {
  std::vector<BinPart> parts;  // the parts at rest in the bin; instance ids 0..n-1
  PhysicsResult physics;
  // 8-bit RGB: with the projector's dots and without (room light only).
  cv::Mat im0, im1, im0_passive, im1_passive;
  // Disparity of each view (CV_32FC1, f B / Z - doffs; +inf where no surface).
  cv::Mat disp0, disp1;
  // Left pixels whose surface point the right camera sees too (CV_8UC1 255 / 0).
  cv::Mat nocc0;
  // The left view as a BOP image: rgb = im0_passive, depth, K, poses, masks, gt info.
  AnnotatedImage left;
  // How the bin looks: the settings' fixed values, or those drawn for it (--vary).
  BinVariation variation;
  // The projector as calib.txt gives it and its pattern image (projector_pattern.h).
  ProjectorCalib projector;
  cv::Mat pattern;
  double physics_ms = 0.0, render_ms = 0.0;
};

class BinSimulator {
 public:
  // Checks the settings (InputError naming the option) and prepares what every bin
  // shares: the rig, the parts' hulls, the dot pattern, the bin's mesh.
  BinSimulator(const BinSimSettings& settings, const PartLibrary& parts);
  ~BinSimulator();

  const BinSimSettings& settings() const { return settings_; }
  const StereoRig& rig() const { return rig_; }
  const DotPattern& pattern() const { return *pattern_; }

  // Bin `index` of the data set made with `seed`: a function of (settings, parts, seed,
  // index) only, the same bytes for any thread count.
  BinViews simulate(std::uint32_t seed, std::int64_t index) const;

  // The bin's own mesh (floor and walls, bin frame, mm) and the table's.
  const Mesh& bin_mesh() const { return *bin_mesh_; }

 private:
  BinSimSettings settings_;
  const PartLibrary& parts_;
  StereoRig rig_;
  std::vector<PartHull> hulls_;
  std::unique_ptr<DotPattern> pattern_;
  std::shared_ptr<const Mesh> bin_mesh_, table_mesh_;
};

// The left view's non-occluded pixels from both views' depth and instance images: a
// left pixel's point, moved into the right view by its disparity, is seen there when the
// right pixel on either side of it shows the same instance at the same depth (within
// 0.5 % of the depth, 2 mm at least).
cv::Mat nonoccluded_left(const StereoRig& rig, const cv::Mat& depth0, const cv::Mat& instance0,
                         const cv::Mat& depth1, const cv::Mat& instance1);

// f B / Z - doffs where depth > 0, +inf elsewhere.
cv::Mat disparity_from_depth(const StereoRig& rig, const cv::Mat& depth);

}  // namespace flexsight

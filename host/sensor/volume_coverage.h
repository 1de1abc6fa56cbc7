#pragma once
// Which part of the working volume the sensor sees: every sample of a grid over the box
// is tested against the two camera frustums and the projector's. A point counts for
// depth when all three see it (the active stereo of the paper needs the pattern on it
// and both views of it). Empty space is assumed: nothing in the box hides anything.
#include <array>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "host/sensor/sensor_geometry.h"

namespace flexsight {

// Which devices see a point, as bits.
enum SeenBy : unsigned { kSeenByLeft = 1u, kSeenByRight = 2u, kSeenByProjector = 4u, kSeenByAll = 7u };

// p in the rig frame (stereo_rig.h).
unsigned seen_by(const StereoRig& rig, const Eigen::Vector3d& p);

// Percent of the samples of a region seen by each device and by all three.
struct RegionCoverage {
  std::string name;
  long long samples = 0;
  double left = 0.0, right = 0.0, projector = 0.0, cameras = 0.0, all = 0.0;
};

struct CornerCoverage {
  std::string name;  // "near top left", ... (top: smallest y, left: smallest x)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  unsigned seen = 0;
};

struct VolumeCoverage {
  double step_mm = 0.0;
  int nx = 0, ny = 0, nz = 0;  // cells per axis; samples at the cell centres
  RegionCoverage volume;       // the whole box
  std::vector<RegionCoverage> faces;   // near, far, left, right, top, bottom
  std::vector<RegionCoverage> slabs;   // the box cut along z into equal slabs, near first
  std::array<CornerCoverage, 8> corners;
  // Bounding box of the samples not seen by all three (valid when any is unseen).
  bool any_unseen = false;
  Eigen::Vector3d unseen_min = Eigen::Vector3d::Zero(), unseen_max = Eigen::Vector3d::Zero();
  // Fraction of each column not seen by all three, for the pictures: top view rows z,
  // columns x (nz x nx); side view rows z, columns y (nz x ny).
  cv::Mat1f top_unseen, side_unseen;
};

// Samples the box with cells of about `step_mm` (the number of cells per axis is
// ceil(size / step), centres sampled, so each sample stands for an equal share of the
// volume), faces on the same grid, `slab_count` slabs along z.
VolumeCoverage measure_coverage(const StereoRig& rig, const WorkingVolume& volume, double step_mm,
                                int slab_count = 8);

// Grid cells per axis for a size and step: what measure_coverage will sample (for
// checking a --grid option before the work).
long long cells_along(double size_mm, double step_mm);

}  // namespace flexsight

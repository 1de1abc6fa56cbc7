#pragma once
// Parts found in a measured depth map without knowing which they are: the pixels higher
// than the bin floor (floor_plane.h) by a margin, joined to their neighbours where the
// depth changes little, as connected regions; regions of a part's size that are no bin
// wall give boxes. Stereo depth sees parts the detector misses (it needs no texture or
// training), but cannot split parts that touch at one height.
#include <opencv2/core.hpp>
#include <vector>

#include "host/geometry/pinhole_camera.h"
#include "host/segment/floor_plane.h"

namespace flexsight {

struct DepthSegmentationOptions {
  FloorPlaneOptions floor;
  // Pixels at most this high above the floor (mm) are floor: stereo noise and the parts'
  // lowest rims, which would join neighbours lying on the floor.
  double margin_mm = 6.0;
  // Neighbouring pixels belong to one region while their depths differ by less than this
  // fraction of the depth (6 mm at 1.25 m: a surface as steep as 80 degrees at 0.75 mm a
  // pixel; a part lying on another is a bigger step).
  double step_ratio = 0.005;
  // The parts' smallest and largest diameters (mm): a region's extent (its box's diagonal
  // at its median depth) must lie within [min_extent x smallest, max_extent x largest].
  double smallest_part_mm = 0.0;
  double largest_part_mm = 0.0;
  double min_extent = 0.5;
  double max_extent = 1.2;
  // ... and its area (pixels at its median depth, mm^2) at least (min_area x smallest)^2:
  // the slivers stereo leaves along the bin's walls and the parts' shadows have a long
  // box but few pixels.
  double min_area = 0.5;
  // A region whose points lie on a plane (thickness below this share of its extent)
  // tilted more than wall_tilt_deg from the floor is a bin wall.
  double wall_flatness = 0.05;
  double wall_tilt_deg = 60.0;
  // A region whose box lies this much (share of its area) inside the box of a larger
  // kept region is a piece of that part (a pin, a rim a step higher) and is dropped.
  double nested_share = 0.8;
  void check() const;
};

// One region kept as a part.
struct DepthRegion {
  int label = 0;          // in DepthSegmentation::labels
  cv::Rect box;           // pixels
  int pixels = 0;
  double depth_mm = 0.0;  // median
  double extent_mm = 0.0; // the box's diagonal at that depth
  double area_mm2 = 0.0;  // its pixels at that depth
  // pixels / box area: a compact region (one part) scores near 1 for boxy parts, a
  // thin sliver or a ring low.
  double score = 0.0;
};

struct DepthSegmentation {
  FloorPlane floor;
  // CV_32SC1: 0 the floor or no measurement, else the region's label (every connected
  // region above the floor, kept or not).
  cv::Mat labels;
  int region_count = 0;            // labels 1..region_count
  std::vector<DepthRegion> regions;  // the kept ones, by label
};

// `depth_mm`: CV_32FC1, 0 or not finite where unknown; `camera`: its intrinsics.
// InputError for options that check() refuses (no part sizes given).
DepthSegmentation segment_depth(const cv::Mat& depth_mm, const PinholeCamera& camera,
                                const DepthSegmentationOptions& options);

}  // namespace flexsight

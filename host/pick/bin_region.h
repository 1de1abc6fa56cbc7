#pragma once
// Where a bin's contents can be, read from a coarse disparity of the whole pair: the
// image rectangle of the bin (its floor, the parts on it, the walls and their rims) and
// the disparities found there. The matcher need not search outside either (docs/pick.md,
// "Stereo where it matters"). Works on any camera and renderer: it needs no bin
// description, only the floor (host/segment/floor_plane.h) and that the bin stands out
// from what lies below its floor (a table, or nothing measured).
#include <opencv2/core.hpp>

#include "host/geometry/stereo_camera.h"
#include "host/pick/stereo_region.h"
#include "host/segment/floor_plane.h"

namespace flexsight {

struct BinRegionOptions {
  // Pixels deeper than the floor by more than this (mm) lie outside the bin: the table
  // under it (a bin's bottom is a centimetre or more thick) or the room beyond. Well
  // above the coarse match's noise on the floor, about 2-3 mm at 1/8 size and 1.4 m.
  double below_floor_mm = 5.0;
  // The bin is the largest connected set of pixels at or above the floor, after an
  // opening with a square of this side (pixels of the full image) that cuts the thin
  // bridges a coarse match leaves between the bin and the table.
  int opening_px = 9;
  // The rectangle grows by this many pixels on each side (the coarse match's blurred
  // rims), and the disparity range by this many pixels at each end.
  int rect_margin_px = 16;
  int disparity_margin = 8;
  FloorPlaneOptions floor;
  void check() const;
};

struct BinRegion {
  cv::Rect rect;          // inside the image
  DisparityRange range;   // full-resolution disparities, min >= 0
  bool found = false;     // false: no floor or no bin found; rect is the whole image
  FloorPlane floor;
};

// `disparity`: CV_32FC1 of the pair's full size (a coarse match brought back to it); `rig`:
// the pair's calibration at that size; `ndisp`: the pair's search range, which the region's
// range never exceeds. Not found: the whole image and [0, ndisp - 1].
BinRegion find_bin_region(const cv::Mat& disparity, const StereoCamera& rig, int ndisp,
                          const BinRegionOptions& options = BinRegionOptions());

}  // namespace flexsight

#pragma once
// The geometry of a stereo sensor with a pattern projector (the FlexSight C1 of the
// paper, Sec. III, Fig. 3): two cameras on the x axis, a baseline apart, and a projector
// between them, all looking along +z; and the box they must see. Units: mm and pixels.
//
// The cameras are modelled as the matcher sees them: rectified and parallel, with the
// principal points shifted horizontally by -doffs/2 (left) and +doffs/2 (right), which
// is Middlebury's doffs convention (Z = f B / (d + doffs)). A converging (toed-in) rig
// becomes exactly this after rectification, up to the warp of the image borders, and
// disparities exist only on rectified images; so depth resolution and disparity range are
// those of this model whatever the mechanical toe-in, and a positive doffs is the
// rectified form of a rig aimed at the volume.
#include <array>
#include <string>

namespace flexsight {

struct Point3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

// The working volume: an axis-aligned box centred on the middle axis (x = y = 0) at
// z = distance. width along x (the baseline), height along y, depth along z.
struct WorkingVolume {
  double width = 600.0, height = 400.0, depth = 400.0;
  double distance = 1250.0;

  double near_z() const { return distance - depth / 2.0; }
  double far_z() const { return distance + depth / 2.0; }
  double min_x() const { return -width / 2.0; }
  double max_x() const { return width / 2.0; }
  double min_y() const { return -height / 2.0; }
  double max_y() const { return height / 2.0; }
  // Corner i: bit 0 picks max x, bit 1 max y, bit 2 the far plane.
  Point3 corner(int i) const;
  double volume_mm3() const { return width * height * depth; }
};

// A pinhole camera with centre (x, 0, 0), looking along +z, image x to the right of the
// baseline's direction, y down; the image spans [0, width] x [0, height] (pixel corners).
struct PinholeCamera {
  double centre_x = 0.0;
  double focal_px = 0.0;
  double cx = 0.0, cy = 0.0;
  int width = 0, height = 0;

  // Image position of p; false (and u, v untouched) when p is not in front (z <= 0).
  bool project(const Point3& p, double& u, double& v) const;
  // Whether p lands in the image; the border counts (a volume that fits exactly is seen).
  bool sees(const Point3& p) const;
};

// The pattern projector: a symmetric frustum, apex (centre_x, 0, 0), axis +z.
struct Projector {
  double centre_x = 0.0;
  double hfov_deg = 35.0, vfov_deg = 35.0;
  bool sees(const Point3& p) const;
};

struct StereoRig {
  double baseline_mm = 500.0;
  double focal_px = 0.0;
  int width = 4000, height = 3000;
  // cx(right) - cx(left), px; Middlebury's doffs. Each principal point moves by half.
  double doffs_px = 0.0;
  Projector projector;

  PinholeCamera left() const;   // centre at -baseline / 2
  PinholeCamera right() const;  // centre at +baseline / 2
  // The disparity xL - xR of a point at depth z: f B / z - doffs (any x, y).
  double disparity_at(double z) const;
};

// f = (width / 2) / tan(hfov / 2), and back.
double focal_from_hfov(double hfov_deg, int width);
double hfov_from_focal(double focal_px, int width);

// The depth step that one disparity step delta_d makes at depth z: differentiating
// Z = f B / (d + doffs) gives dZ = Z^2 delta_d / (f B) (doffs drops out).
double depth_step(double z, double focal_px, double baseline_mm, double subpixel_px);
// The focal length (px) at which depth_step(z, ...) == step_mm, and the disparity step
// at which it does for a given focal length: the same formula solved for f or delta_d.
double focal_for_depth_step(double z, double step_mm, double baseline_mm, double subpixel_px);
double subpixel_for_depth_step(double z, double step_mm, double focal_px, double baseline_mm);

// The doffs that centres the volume's horizontal extent in each camera's image (the
// extent of (x - centre) / z over the box's corners; the volume is symmetric about the
// middle axis, so one doffs centres it in both): the best use of the pixels, and what a
// rig aimed at the volume gives after rectification. Scales with the focal length.
double centring_doffs(double focal_px, double baseline_mm, const WorkingVolume& volume);

// The largest focal length at which the whole volume fits in both images with the
// centring doffs: min(width / horizontal tangent extent, (height / 2) / max |y / z|).
double fitting_focal(double baseline_mm, const WorkingVolume& volume, int width, int height);

}  // namespace flexsight

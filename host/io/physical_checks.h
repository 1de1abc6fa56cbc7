#pragma once
// Ranges that a pose, a camera or a box read from a file must lie in to describe
// something physical. Every reader of poses, intrinsics and boxes (BOP and COCO files,
// results, templates) checks its values with these, so that a value no camera or part
// could have is refused where it is read, with the file named, rather than deep in a
// renderer or a search (docs/reliability.md lists the ranges).
// Each function returns the problem as text ("" when the value is fine); the caller puts
// the file and entry in front: "<file>: <entry>: <name> <problem>".
#include <Eigen/Core>
#include <string>

namespace flexsight::physical_checks {

// How far R^T R may be from the identity, entry by entry, and det(R) from +1 (or -1 for
// a mirrored pose): results printed with 6 to 8 digits (as many writers do) are off by
// about 1e-6.
constexpr double kRotationTolerance = 1e-3;
// A translation of a part in front of the camera, in mm: 100 m is beyond any bin.
constexpr double kMaxTranslationMm = 1e5;
// Focal lengths in pixels: 1e6 px is a 3 degree field of view over 50,000 pixels.
constexpr double kMaxFocalPx = 1e6;
// The principal point may lie off the image (a crop), but within this many pixels.
constexpr double kMaxPrincipalPointPx = 1e6;
// Millimetres per unit of a 16-bit depth PNG: 65535 x 100 mm is 6.5 km.
constexpr double kMaxDepthScale = 100.0;
// Box coordinates in pixels, where the image size is not known.
constexpr double kMaxBoxPx = 1e6;

// R is orthonormal within kRotationTolerance and det(R) is within it of +1, or of -1
// when `mirrored` (the poses of an image flipped once, annotated_image.h). The problem
// reads "is not a rotation: ..." or "is a reflection, not a rotation (det ...)".
std::string rotation_problem(const Eigen::Matrix3d& R, bool mirrored = false);

// t (mm) is finite, within kMaxTranslationMm of the camera and, when `in_front`, in
// front of it (z > 0). Ground truth must be in front; an estimate need not (a failed
// search may return the origin, which scores as a miss, not as a broken file).
std::string translation_problem(const Eigen::Vector3d& t_mm, bool in_front);

// K = [fx s cx; 0 fy cy; 0 0 1]: finite, fx and fy in (0, kMaxFocalPx], |cx| and |cy|
// within kMaxPrincipalPointPx.
std::string intrinsics_problem(const Eigen::Matrix3d& K);

// A depth PNG's scale: in (0, kMaxDepthScale].
std::string depth_scale_problem(double depth_scale);

// The shortest text that reads back to the same double; whole numbers below 1e15 as
// integers.
std::string number_text(double value);

}  // namespace flexsight::physical_checks

#include "host/io/physical_checks.h"

#include <Eigen/LU>
#include <charconv>
#include <cmath>

namespace flexsight::physical_checks {

std::string number_text(double value) {
  // Whole numbers of a limit read better written out: 100000, not 1e+05.
  if (std::fabs(value) < 1e15 && std::nearbyint(value) == value) {
    return std::to_string(static_cast<long long>(value));
  }
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string rotation_problem(const Eigen::Matrix3d& R, bool mirrored) {
  if (!R.allFinite()) return "is not a rotation: it has a value that is not finite";
  const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (off > kRotationTolerance) {
    return "is not a rotation: |R^T R - I| reaches " + number_text(off) + " (at most " +
           number_text(kRotationTolerance) + ")";
  }
  const double det = R.determinant();
  const double expected = mirrored ? -1.0 : 1.0;
  if (det * expected < 0) {
    return mirrored ? "is a rotation, but the image is flipped once: det " + number_text(det) +
                          " (expected -1, a reflection)"
                    : "is a reflection, not a rotation (det " + number_text(det) + ")";
  }
  if (std::fabs(det - expected) > kRotationTolerance) {
    return "is not a rotation: det " + number_text(det) + " (expected " + number_text(expected) +
           " within " + number_text(kRotationTolerance) + ")";
  }
  return "";
}

std::string translation_problem(const Eigen::Vector3d& t_mm, bool in_front) {
  if (!t_mm.allFinite()) return "has a value that is not finite";
  if (in_front && !(t_mm.z() > 0)) {
    return "puts the part behind the camera or in its centre (z = " + number_text(t_mm.z()) +
           " mm; z must be positive)";
  }
  // stableNorm: the plain norm's squares overflow beyond 1e154.
  if (t_mm.stableNorm() > kMaxTranslationMm) {
    return "[" + number_text(t_mm.x()) + ", " + number_text(t_mm.y()) + ", " +
           number_text(t_mm.z()) + "] is farther than " + number_text(kMaxTranslationMm) +
           " mm from the camera";
  }
  return "";
}

std::string intrinsics_problem(const Eigen::Matrix3d& K) {
  if (!K.allFinite()) return "has a value that is not finite";
  const double fx = K(0, 0), fy = K(1, 1);
  if (!(fx > 0 && fy > 0 && fx <= kMaxFocalPx && fy <= kMaxFocalPx)) {
    return "focal lengths fx = " + number_text(fx) + ", fy = " + number_text(fy) +
           " must be in (0, " + number_text(kMaxFocalPx) + "] pixels";
  }
  if (std::fabs(K(0, 2)) > kMaxPrincipalPointPx || std::fabs(K(1, 2)) > kMaxPrincipalPointPx) {
    return "principal point (" + number_text(K(0, 2)) + ", " + number_text(K(1, 2)) +
           ") is beyond " + number_text(kMaxPrincipalPointPx) + " pixels";
  }
  return "";
}

std::string depth_scale_problem(double depth_scale) {
  if (!(depth_scale > 0)) return "must be positive";
  if (!(depth_scale <= kMaxDepthScale)) {
    return number_text(depth_scale) + " is beyond " + number_text(kMaxDepthScale) +
           " mm per depth unit";
  }
  return "";
}

}  // namespace flexsight::physical_checks

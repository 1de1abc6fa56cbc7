#pragma once
// The parts' symmetries as BOP keeps them (models_info.json of a BOP data set's models
// folder, the BOP toolkit's docs/bop_datasets_format.md) and their discretisation into
// the finite set of transformations the symmetry-aware pose errors (MSSD, MSPD) take the
// minimum over (bop_toolkit_lib/misc.py, get_symmetry_transformations).
//
// models_info.json maps each object id (a string key, "5") to an object with
//   diameter                  largest distance between two model vertices (mm)
//   min_x, min_y, min_z       the corner of the model's bounding box (optional here)
//   size_x, size_y, size_z    its extent (optional here)
//   symmetries_discrete       (optional) list of 4x4 matrices, row-major, t in mm:
//                             x -> R x + t maps the model onto itself
//   symmetries_continuous     (optional) list of {"axis": [3], "offset": [3]}: every
//                             rotation about the axis through the offset point does
// The identity is never listed: it is always a symmetry.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace flexsight {

// x -> R x + t in the model frame (mm).
struct SymmetryTransform {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
};

// Every rotation about the line through `offset` along `axis` (unit length once read).
struct ContinuousSymmetry {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
};

struct ModelInfo {
  int obj_id = 0;
  double diameter = 0.0;  // mm
  // Bounding box; has_box is false when min_* / size_* were not all given.
  bool has_box = false;
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), size = Eigen::Vector3d::Zero();
  std::vector<SymmetryTransform> symmetries_discrete;    // as listed (no identity)
  std::vector<ContinuousSymmetry> symmetries_continuous;
  // Any symmetry besides the identity (ADD-S rather than ADD applies).
  bool symmetric() const { return !symmetries_discrete.empty() || !symmetries_continuous.empty(); }
};

// BOP's step: a continuous symmetry is sampled so that no vertex moves more than this
// fraction of the diameter between neighbouring rotations (eval_bop19_pose.py's
// max_sym_disc_step).
constexpr double kBopMaxSymmetryStep = 0.01;

// Reads a models_info.json, by obj_id. Throws InputError naming the file and the object
// ("obj 5: ...") for a file that is missing or not JSON, a key that is not a whole number,
// a diameter that is missing or not positive, a symmetry matrix that is not 16 finite
// numbers with last row 0 0 0 1 and a rotation (|R^T R - I| <= 1e-3, det > 0) in its
// top-left block, a continuous symmetry without a non-zero axis or a 3-number offset,
// and keys of the wrong type.
std::map<int, ModelInfo> read_models_info(const std::string& path);

// The symmetry transformations of `info` as bop_toolkit's get_symmetry_transformations
// makes them: the identity and the discrete ones; each continuous symmetry sampled at
// n = ceil(pi / max_step) rotations i * 2 pi / n, i = 0..n-1, about its axis through its
// offset (t = offset - R offset); then every discrete transformation (identity first)
// composed with every continuous sample (continuous after discrete). The identity is the
// first element. max_step must be positive.
std::vector<SymmetryTransform> symmetry_transformations(const ModelInfo& info,
                                                        double max_step = kBopMaxSymmetryStep);

}  // namespace flexsight

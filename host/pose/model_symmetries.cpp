#include "host/pose/model_symmetries.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

#include "host/dataset/dataset_files.h"
#include "host/io/input_error.h"

namespace flexsight {
namespace {

namespace df = dataset_files;

// How far a listed symmetry's R^T R may be from the identity: models_info files print
// their matrices with 6 to 8 digits.
constexpr double kRotationTolerance = 1e-3;

int parse_obj_id(const std::string& key, const std::string& path) {
  const bool digits =
      !key.empty() && key.size() <= 9 && key.find_first_not_of("0123456789") == std::string::npos;
  if (!digits) throw InputError(path, "key \"" + key + "\": expected an object id (a whole number >= 0)");
  return std::stoi(key);
}

SymmetryTransform read_discrete(const df::Json& value, const std::string& path, const std::string& where) {
  const std::vector<double> m = df::to_doubles(value, 16, path, where);
  for (double x : m) {
    if (!std::isfinite(x)) throw InputError(path, where + ": a value is not finite");
  }
  if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1) {
    throw InputError(path, where + ": the last row must be 0 0 0 1 (a rigid transformation)");
  }
  SymmetryTransform s;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) s.R(row, col) = m[4 * row + col];
    s.t(row) = m[4 * row + 3];
  }
  const double off = (s.R.transpose() * s.R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (off > kRotationTolerance || s.R.determinant() <= 0) {
    throw InputError(path, where + ": the top-left 3x3 block is not a rotation");
  }
  return s;
}

ContinuousSymmetry read_continuous(const df::Json& value, const std::string& path, const std::string& where) {
  ContinuousSymmetry s;
  const std::vector<double> axis = df::to_doubles(df::require_key(value, "axis", path, where), 3, path, where + ": axis");
  const std::vector<double> offset =
      df::to_doubles(df::require_key(value, "offset", path, where), 3, path, where + ": offset");
  s.axis = Eigen::Vector3d(axis[0], axis[1], axis[2]);
  s.offset = Eigen::Vector3d(offset[0], offset[1], offset[2]);
  const double length = s.axis.norm();
  if (!(length > 0) || !std::isfinite(length) || !s.offset.allFinite()) {
    throw InputError(path, where + ": axis must be a non-zero vector and offset finite");
  }
  s.axis /= length;
  return s;
}

ModelInfo read_model(int obj_id, const df::Json& entry, const std::string& path) {
  const std::string where = "obj " + std::to_string(obj_id);
  if (!entry.is_object()) throw InputError(path, where + ": expected an object");
  ModelInfo info;
  info.obj_id = obj_id;
  info.diameter = df::to_double(df::require_key(entry, "diameter", path, where), path, where + ": diameter");
  if (!(info.diameter > 0) || !std::isfinite(info.diameter)) {
    throw InputError(path, where + ": diameter must be a positive number");
  }
  const char* axes = "xyz";
  int box_keys = 0;
  for (int k = 0; k < 3; ++k) {
    const std::string min_key = std::string("min_") + axes[k], size_key = std::string("size_") + axes[k];
    if (entry.contains(min_key)) {
      info.min(k) = df::to_double(entry[min_key], path, where + ": " + min_key);
      ++box_keys;
    }
    if (entry.contains(size_key)) {
      info.size(k) = df::to_double(entry[size_key], path, where + ": " + size_key);
      ++box_keys;
    }
  }
  info.has_box = box_keys == 6;
  if (entry.contains("symmetries_discrete")) {
    const df::Json& list = entry["symmetries_discrete"];
    if (!list.is_array()) throw InputError(path, where + ": symmetries_discrete: expected a list");
    for (std::size_t i = 0; i < list.size(); ++i) {
      info.symmetries_discrete.push_back(
          read_discrete(list[i], path, where + ": symmetries_discrete[" + std::to_string(i) + "]"));
    }
  }
  if (entry.contains("symmetries_continuous")) {
    const df::Json& list = entry["symmetries_continuous"];
    if (!list.is_array()) throw InputError(path, where + ": symmetries_continuous: expected a list");
    for (std::size_t i = 0; i < list.size(); ++i) {
      info.symmetries_continuous.push_back(
          read_continuous(list[i], path, where + ": symmetries_continuous[" + std::to_string(i) + "]"));
    }
  }
  return info;
}

}  // namespace

std::map<int, ModelInfo> read_models_info(const std::string& path) {
  const df::Json json = df::read_json(path);
  if (!json.is_object()) throw InputError(path, "expected a JSON object keyed by object id");
  std::map<int, ModelInfo> table;
  for (const auto& [key, entry] : json.items()) {
    const int obj_id = parse_obj_id(key, path);
    if (table.count(obj_id)) throw InputError(path, "object id " + std::to_string(obj_id) + " is listed twice");
    table.emplace(obj_id, read_model(obj_id, entry, path));
  }
  return table;
}

std::vector<SymmetryTransform> symmetry_transformations(const ModelInfo& info, double max_step) {
  if (!(max_step > 0)) throw std::invalid_argument("symmetry_transformations: max_step must be positive");
  std::vector<SymmetryTransform> discrete{SymmetryTransform{}};
  discrete.insert(discrete.end(), info.symmetries_discrete.begin(), info.symmetries_discrete.end());

  // A vertex at the distance r <= diameter from the axis moves by the chord
  // 2 r sin(step / 2) < r * 2 pi / n <= 2 r max_step between neighbouring samples.
  std::vector<SymmetryTransform> continuous;
  const int steps = static_cast<int>(std::ceil(M_PI / max_step));
  for (const ContinuousSymmetry& symmetry : info.symmetries_continuous) {
    for (int i = 0; i < steps; ++i) {
      SymmetryTransform s;
      s.R = Eigen::AngleAxisd(i * 2.0 * M_PI / steps, symmetry.axis.normalized()).toRotationMatrix();
      s.t = symmetry.offset - s.R * symmetry.offset;
      continuous.push_back(s);
    }
  }
  if (continuous.empty()) return discrete;

  std::vector<SymmetryTransform> all;
  for (const SymmetryTransform& d : discrete) {
    for (const SymmetryTransform& c : continuous) {
      all.push_back({c.R * d.R, c.R * d.t + c.t});
    }
  }
  return all;
}

}  // namespace flexsight

#pragma once
// The pose errors of the BOP benchmark (Hodan et al., "BOP Challenge 2020 on 6D Object
// Localization", ECCVW 2020; bop_toolkit_lib/pose_error.py), between an estimated and a
// ground-truth pose of one part:
//   ADD    mean distance between the model's vertices at the two poses (Hinterstoisser
//          et al., ACCV 2012)
//   ADD-S  mean distance from each vertex at the true pose to the nearest vertex at the
//          estimated pose (the same paper's "ADI", for parts with symmetries)
//   MSSD   the largest vertex distance, minimised over the part's symmetries (mm)
//   MSPD   the same for the vertices' projections into the image (pixels)
//   VSD    the share of the visible surface whose depth differs by tau or more between
//          the two poses (needs the test image's depth)
// The model points are the mesh's vertices, in mm, as BOP takes the vertices of its
// models (BOP uses "models_eval", meshes resampled to near-uniform vertex density; ours
// are the CAD meshes as they are, denser on curved surfaces).
#include <Eigen/Core>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "host/pose/model_symmetries.h"
#include "host/render/mesh.h"
#include "host/render/raycaster.h"

namespace flexsight {

// A part as the errors need it: vertices, diameter, symmetries and a k-d tree over the
// vertices (nanoflann) for ADD-S. Built once per part; const methods are thread-safe.
class PoseErrorModel {
 public:
  // `diameter` (mm): what thresholds are relative to (models_info.json's). `symmetries`:
  // symmetry_transformations() of the part, the identity first. `symmetric`: whether the
  // part has any symmetry besides the identity (ADD-S rather than ADD applies).
  // Throws std::invalid_argument for a mesh without vertices, a diameter that is not
  // positive, or no symmetry (the identity at least).
  PoseErrorModel(std::shared_ptr<const Mesh> mesh, double diameter,
                 std::vector<SymmetryTransform> symmetries, bool symmetric);
  ~PoseErrorModel();
  PoseErrorModel(PoseErrorModel&&) noexcept;
  PoseErrorModel& operator=(PoseErrorModel&&) noexcept;

  const Mesh& mesh() const;
  const std::shared_ptr<const Mesh>& shared_mesh() const;
  double diameter() const;
  bool symmetric() const;
  const std::vector<SymmetryTransform>& symmetries() const;
  // The vertices, farthest from the box centre first: the largest errors of a pose tend
  // to be there, so the searches for a maximum can stop early.
  const std::vector<Eigen::Vector3d>& points() const;
  // Distance from `p` (model frame, mm) to the nearest vertex.
  double nearest_vertex_distance(const Eigen::Vector3d& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Errors in mm (MSPD in pixels). Poses map model points to the camera frame.
double add_error(const PoseErrorModel& model, const Pose& estimate, const Pose& truth);
double adds_error(const PoseErrorModel& model, const Pose& estimate, const Pose& truth);
// ADD-S for a symmetric part, ADD otherwise: BOP's "ADD(-S)".
double add_or_adds_error(const PoseErrorModel& model, const Pose& estimate, const Pose& truth);
double mssd_error(const PoseErrorModel& model, const Pose& estimate, const Pose& truth);
// `K`: the image's intrinsics (pixel = K x / z).
double mspd_error(const PoseErrorModel& model, const Pose& estimate, const Pose& truth,
                  const Eigen::Matrix3d& K);

// The depth of one part alone at a pose, ray cast (host/render/raycaster.h), for VSD.
class ModelDepthRenderer {
 public:
  explicit ModelDepthRenderer(std::shared_ptr<const Mesh> mesh);
  // CV_32FC1 of the camera's size: z of the part's surface in mm, 0 elsewhere. Only the
  // pixels of the part's projected bounding box are cast.
  cv::Mat depth(const Pose& pose, const PinholeCamera& camera);

 private:
  RenderScene scene_;
  int instance_ = 0;
};

// BOP's relative thresholds 0.05, 0.10, ..., 0.50, computed as numpy's
// arange(0.05, 0.51, 0.05) computes them (0.05 + i * 0.05, so 0.15000000000000002), so
// that values on a threshold fall on the same side as in the BOP toolkit.
std::vector<double> bop_fraction_thresholds();

// BOP 2019+ VSD settings: delta the visibility tolerance (mm), taus the misalignment
// tolerances as fractions of the diameter (pixel distances are divided by it: BOP's
// vsd_normalized_by_diameter), the step cost.
struct VsdSettings {
  double delta_mm = 15.0;
  std::vector<double> taus = bop_fraction_thresholds();
};

// VSD for every tau of `settings`, as bop_toolkit's pose_error.vsd with cost "step" and
// visibility "bop19": depths are turned into distances from the camera centre; a pixel
// of a rendered part is visible where it is at most delta behind the test depth or the
// test depth is missing (0); the estimate's visible pixels also include those visible at
// the truth where the estimate has a surface. Over the union U of the two visible masks:
// (pixels of the intersection whose distances differ by >= tau * diameter, plus pixels
// of U outside the intersection) / |U|; 1 for an empty union. All images CV_32FC1 in mm
// of one size, `K` their intrinsics.
std::vector<double> vsd_errors(const cv::Mat& depth_test, const cv::Mat& depth_estimate,
                               const cv::Mat& depth_truth, const Eigen::Matrix3d& K, double diameter,
                               const VsdSettings& settings = {});

}  // namespace flexsight

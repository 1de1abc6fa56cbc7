#pragma once
// Point-to-plane ICP of a scene cloud (stereo points in the camera frame) against a CAD
// part's surface, for the last millimetres of a pose that the edge-based search has
// brought close.
//
// The scene is the source and the model the target: each scene point is matched to its
// nearest model point and the distance measured along the model's normal there. The
// normals of the CAD model are exact, while normals estimated from the stereo cloud are
// noisy (a few neighbours, half a millimetre of noise along the rays); and the scene may
// hold background and other parts, which the distance gate rejects point by point
// without having to cut the model's surface to what the camera saw.
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "host/render/raycaster.h"

namespace flexsight {

struct IcpParams {
  // Upper bound on the number of linearised updates.
  int max_iterations = 30;
  // Correspondences farther than this (mm) at the start are outliers: about the error
  // of the pose the fit starts from.
  double max_distance_mm = 10.0;
  // The gate shrinks towards this (mm) as the fit converges: a few times the noise of
  // the scene points and the spacing of the model's points.
  double final_max_distance_mm = 3.0;
  // Stop when the update moves the model less than this (mm): the largest displacement
  // of any model point.
  double convergence_mm = 0.01;
  // Throws InputError naming the field for a value out of range or not finite.
  void check() const;
};

struct IcpResult {
  Pose pose;                      // model -> camera
  int iterations = 0;             // updates applied
  int inliers = 0;                // scene points within the final gate
  double rms_mm = 0.0;            // point-to-plane RMS over the inliers
  double inlier_fraction = 0.0;   // inliers / scene points given
  // The last update moved the model less than convergence_mm with the gate at
  // final_max_distance_mm. False when the iterations ran out, or too few scene points
  // met the model to determine a pose (the pose is then the last good one).
  bool converged = false;
};

// The target is the model's surface (points and unit normals in the model frame); its
// k-d tree is built once here and reused by every refine().
class PointToPlaneIcp {
 public:
  // std::invalid_argument when the two vectors differ in length.
  PointToPlaneIcp(std::vector<Eigen::Vector3f> model_points,
                  std::vector<Eigen::Vector3f> model_normals);
  ~PointToPlaneIcp();
  PointToPlaneIcp(PointToPlaneIcp&&) noexcept;
  PointToPlaneIcp& operator=(PointToPlaneIcp&&) noexcept;

  // Scene points in the camera frame (they may include background and other parts:
  // those are rejected by the distance gate); `initial` maps model to camera. Throws
  // InputError from params.check().
  IcpResult refine(const std::vector<Eigen::Vector3f>& scene_points, const Pose& initial,
                   const IcpParams& params) const;

 private:
  // The points, normals and k-d tree, behind a pointer because the tree keeps a
  // reference to the points it indexes.
  struct Model;
  std::unique_ptr<Model> model_;
};

}  // namespace flexsight

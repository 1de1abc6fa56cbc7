#include "host/pose/point_to_plane_icp.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <nanoflann.hpp>
#include <stdexcept>
#include <string>

#include "host/io/input_error.h"
#include "host/pose/pose_math.h"

namespace flexsight {
namespace {

// Six unknowns; a solve from fewer than twice as many weighted pairs is not trusted.
constexpr int kMinimumPairs = 12;

// Tukey's biweight constant for 95 % efficiency under Gaussian residuals.
constexpr double kTukeyC = 4.685;

// nanoflann's view of the model points.
struct PointsAdaptor {
  const std::vector<Eigen::Vector3f>* points;
  size_t kdtree_get_point_count() const { return points->size(); }
  float kdtree_get_pt(std::uint32_t index, size_t dim) const { return (*points)[index][dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;  // let nanoflann compute it
  }
};

using KdTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointsAdaptor>,
                                        PointsAdaptor, 3>;

void require(bool ok, const std::string& field, const std::string& problem) {
  if (!ok) throw InputError("icp " + field, problem);
}

bool finite_positive(double value) { return std::isfinite(value) && value > 0.0; }

// A scene point brought into the model frame and the model point nearest to it.
struct Pair {
  Eigen::Vector3d scene;
  std::uint32_t model;
};

// Tukey's biweight of residual r at scale c: 1 at 0, falling smoothly to 0 at |r| = c.
double tukey_weight(double r, double c) {
  if (std::abs(r) >= c) return 0.0;
  const double u = r / c;
  return (1.0 - u * u) * (1.0 - u * u);
}

double median_absolute(std::vector<double> values) {
  for (double& v : values) v = std::abs(v);
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

struct PointToPlaneIcp::Model {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;
  PointsAdaptor adaptor;
  KdTree tree;
  // A ball around the points, to bound how far an update moves any of them.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;

  Model(std::vector<Eigen::Vector3f> model_points, std::vector<Eigen::Vector3f> model_normals)
      : points(std::move(model_points)),
        normals(std::move(model_normals)),
        adaptor{&points},
        tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    for (const Eigen::Vector3f& p : points) centre += p.cast<double>();
    if (!points.empty()) centre /= double(points.size());
    for (const Eigen::Vector3f& p : points) {
      radius = std::max(radius, (p.cast<double>() - centre).norm());
    }
  }

  // The scene points (camera frame) whose nearest model point, with the scene brought
  // into the model frame by `pose`, lies within `gate` mm.
  std::vector<Pair> match(const std::vector<Eigen::Vector3f>& scene, const Pose& pose,
                          double gate) const {
    std::vector<Pair> pairs;
    if (points.empty()) return pairs;
    const Eigen::Matrix3d Rt = pose.R.transpose();
    const float bound = search_bound(gate * gate);
    // A scene point this far from the ball has no model point within the gate; a
    // millimetre of slack covers the float rounding of the tree's distances.
    const double reach = radius + gate + 1.0;
    const double reach_squared = reach * reach;
    for (const Eigen::Vector3f& p : scene) {
      if (!p.allFinite()) continue;
      const Eigen::Vector3d q = Rt * (p.cast<double>() - pose.t);
      if ((q - centre).squaredNorm() > reach_squared) continue;
      const Eigen::Vector3f query = q.cast<float>();
      std::uint32_t nearest = 0;
      float distance_squared = 0.0f;
      // Searched with the gate as the worst distance from the start, the tree prunes
      // every cell beyond it: the same nearest point when one lies within the gate,
      // none otherwise, for a fraction of the visits (most scene points of a box are
      // the floor and the neighbours, far from the model).
      nanoflann::KNNResultSet<float, std::uint32_t> nearest_within_gate(1);
      nearest_within_gate.init(&nearest, &distance_squared);
      distance_squared = bound;
      tree.findNeighbors(nearest_within_gate, query.data(), nanoflann::SearchParams());
      if (nearest_within_gate.size() == 1) pairs.push_back({q, nearest});
    }
    return pairs;
  }

  // The float d that keeps exactly the tree distances (floats) at most `gate_squared`
  // by the tree's own test, distance < d.
  static float search_bound(double gate_squared) {
    float largest_within = static_cast<float>(gate_squared);
    if (static_cast<double>(largest_within) > gate_squared) {
      largest_within = std::nextafter(largest_within, -std::numeric_limits<float>::infinity());
    }
    return std::nextafter(largest_within, std::numeric_limits<float>::infinity());
  }

  double residual(const Pair& pair) const {
    return (pair.scene - points[pair.model].cast<double>()).dot(normals[pair.model].cast<double>());
  }
};

void IcpParams::check() const {
  require(max_iterations >= 1, "max_iterations",
          "must be at least 1, got " + std::to_string(max_iterations));
  require(finite_positive(max_distance_mm), "max_distance_mm",
          "must be finite and > 0, got " + std::to_string(max_distance_mm));
  require(finite_positive(final_max_distance_mm) && final_max_distance_mm <= max_distance_mm,
          "final_max_distance_mm",
          "must be > 0 and <= max_distance_mm, got " + std::to_string(final_max_distance_mm));
  require(finite_positive(convergence_mm), "convergence_mm",
          "must be finite and > 0, got " + std::to_string(convergence_mm));
}

PointToPlaneIcp::PointToPlaneIcp(std::vector<Eigen::Vector3f> model_points,
                                 std::vector<Eigen::Vector3f> model_normals) {
  if (model_points.size() != model_normals.size()) {
    throw std::invalid_argument("PointToPlaneIcp: " + std::to_string(model_points.size()) +
                                " model points but " + std::to_string(model_normals.size()) +
                                " normals");
  }
  for (size_t i = 0; i < model_points.size(); ++i) {
    const float length = model_normals[i].norm();
    if (!model_points[i].allFinite() || !std::isfinite(length) || length == 0.0f) {
      throw std::invalid_argument("PointToPlaneIcp: model point " + std::to_string(i) +
                                  " is not finite or has no normal");
    }
    model_normals[i] /= length;
  }
  model_ = std::make_unique<Model>(std::move(model_points), std::move(model_normals));
}

PointToPlaneIcp::~PointToPlaneIcp() = default;
PointToPlaneIcp::PointToPlaneIcp(PointToPlaneIcp&&) noexcept = default;
PointToPlaneIcp& PointToPlaneIcp::operator=(PointToPlaneIcp&&) noexcept = default;

IcpResult PointToPlaneIcp::refine(const std::vector<Eigen::Vector3f>& scene_points,
                                  const Pose& initial, const IcpParams& params) const {
  params.check();
  const double final_gate = params.final_max_distance_mm;
  IcpResult result;
  result.pose = initial;
  double gate = params.max_distance_mm;

  for (int iteration = 0; iteration < params.max_iterations; ++iteration) {
    const std::vector<Pair> pairs = model_->match(scene_points, result.pose, gate);
    if (static_cast<int>(pairs.size()) < kMinimumPairs) break;

    // Robust scale of the point-to-plane residuals (MAD). Below a third of the final
    // gate the residuals are at the level of the model's sampling and the scene's noise:
    // weighting them down further would only discard good pairs (and a noise-free scene
    // would have a scale of 0). Above the gate no pair remains anyway.
    std::vector<double> residuals(pairs.size());
    for (size_t i = 0; i < pairs.size(); ++i) residuals[i] = model_->residual(pairs[i]);
    const double sigma = 1.4826 * median_absolute(residuals);
    const double c = std::clamp(kTukeyC * sigma, final_gate / 3.0, gate);

    // Linearised in the small motion (w, d) of the scene in the model frame,
    // q -> q + w x q + d: the residual changes by (q x n) . w + n . d.
    Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
    int weighted = 0;
    for (size_t i = 0; i < pairs.size(); ++i) {
      const double weight = tukey_weight(residuals[i], c);
      if (weight == 0.0) continue;
      ++weighted;
      const Eigen::Vector3d n = model_->normals[pairs[i].model].cast<double>();
      Eigen::Matrix<double, 6, 1> J;
      J << pairs[i].scene.cross(n), n;
      A.selfadjointView<Eigen::Lower>().rankUpdate(J, weight);
      b += weight * residuals[i] * J;
    }
    if (weighted < kMinimumPairs) break;
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(A.selfadjointView<Eigen::Lower>());
    if (ldlt.info() != Eigen::Success) break;
    const Eigen::Matrix<double, 6, 1> x = -ldlt.solve(b);
    if (!x.allFinite()) break;

    // The scene moves by q -> dR q + d in the model frame, i.e. the pose becomes
    // R' = R dR^T, t' = t - R' d.
    const Eigen::Matrix3d dR = rotation_from_axis_angle(x.head<3>());
    const Eigen::Vector3d d = x.tail<3>();
    result.pose.R = result.pose.R * dR.transpose();
    result.pose.t = result.pose.t - result.pose.R * d;
    ++result.iterations;

    // The largest displacement of a model point relative to the scene: that of the
    // ball's centre plus the rotation's chord at its radius.
    const double angle = x.head<3>().norm();
    const double motion = (dR * model_->centre + d - model_->centre).norm() +
                          2.0 * std::sin(angle / 2.0) * model_->radius;
    if (motion < params.convergence_mm) {
      if (gate <= final_gate) {
        result.converged = true;
        break;
      }
      gate = final_gate;
    } else {
      // The gate follows the pose error, estimated by the size of the last step (with a
      // margin of two): wide while the fit moves, the final gate when it has settled.
      gate = std::clamp(final_gate + 2.0 * motion, final_gate, gate);
    }
  }

  // The inliers and their RMS at the pose returned, with the gate reached.
  const std::vector<Pair> inliers = model_->match(scene_points, result.pose, gate);
  double sum_squared = 0.0;
  for (const Pair& pair : inliers) sum_squared += std::pow(model_->residual(pair), 2);
  result.inliers = static_cast<int>(inliers.size());
  result.rms_mm = inliers.empty() ? 0.0 : std::sqrt(sum_squared / inliers.size());
  result.inlier_fraction =
      scene_points.empty() ? 0.0 : double(inliers.size()) / double(scene_points.size());
  return result;
}

}  // namespace flexsight

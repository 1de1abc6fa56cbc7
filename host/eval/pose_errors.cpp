#include "host/eval/pose_errors.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>
#include <stdexcept>

namespace flexsight {
namespace {

// nanoflann's view of the vertices.
struct PointCloudAdaptor {
  const std::vector<Eigen::Vector3d>* points = nullptr;
  std::size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return (*points)[i](static_cast<int>(dim)); }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using VertexTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloudAdaptor>,
                                                       PointCloudAdaptor, 3, std::uint32_t>;

// Where K puts camera-frame point p (BOP's project_pts: K p divided by its third entry).
Eigen::Vector2d project(const Eigen::Matrix3d& K, const Eigen::Vector3d& p) {
  const Eigen::Vector3d h = K * p;
  return h.head<2>() / h(2);
}

}  // namespace

struct PoseErrorModel::Impl {
  std::shared_ptr<const Mesh> mesh;
  double diameter = 0.0;
  bool symmetric = false;
  std::vector<SymmetryTransform> symmetries;
  std::vector<Eigen::Vector3d> points;
  PointCloudAdaptor adaptor;
  std::unique_ptr<VertexTree> tree;
};

PoseErrorModel::PoseErrorModel(std::shared_ptr<const Mesh> mesh, double diameter,
                               std::vector<SymmetryTransform> symmetries, bool symmetric)
    : impl_(std::make_unique<Impl>()) {
  if (!mesh || mesh->positions.empty()) throw std::invalid_argument("PoseErrorModel: a mesh without vertices");
  if (!(diameter > 0)) throw std::invalid_argument("PoseErrorModel: the diameter must be positive");
  if (symmetries.empty()) throw std::invalid_argument("PoseErrorModel: no symmetry (the identity at least)");
  impl_->mesh = std::move(mesh);
  impl_->diameter = diameter;
  impl_->symmetric = symmetric;
  impl_->symmetries = std::move(symmetries);
  const Eigen::Vector3d centre = impl_->mesh->bounds.center().cast<double>();
  for (const Eigen::Vector3f& p : impl_->mesh->positions) impl_->points.push_back(p.cast<double>());
  std::stable_sort(impl_->points.begin(), impl_->points.end(),
                   [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
                     return (a - centre).squaredNorm() > (b - centre).squaredNorm();
                   });
  impl_->adaptor.points = &impl_->points;
  impl_->tree = std::make_unique<VertexTree>(3, impl_->adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  impl_->tree->buildIndex();
}

PoseErrorModel::~PoseErrorModel() = default;
PoseErrorModel::PoseErrorModel(PoseErrorModel&&) noexcept = default;
PoseErrorModel& PoseErrorModel::operator=(PoseErrorModel&&) noexcept = default;

const Mesh& PoseErrorModel::mesh() const { return *impl_->mesh; }
const std::shared_ptr<const Mesh>& PoseErrorModel::shared_mesh() const { return impl_->mesh; }
double PoseErrorModel::diameter() const { return impl_->diameter; }
bool PoseErrorModel::symmetric() const { return impl_->symmetric; }
const std::vector<SymmetryTransform>& PoseErrorModel::symmetries() const { return impl_->symmetries; }
const std::vector<Eigen::Vector3d>& PoseErrorModel::points() const { return impl_->points; }

double PoseErrorModel::nearest_vertex_distance(const Eigen::Vector3d& p) const {
  std::uint32_t index = 0;
  double distance_squared = 0.0;
  impl_->tree->knnSearch(p.data(), 1, &index, &distance_squared);
  return std::sqrt(distance_squared);
}

double add_error(const PoseErrorModel& model, const Pose& estimate, const Pose& truth) {
  double sum = 0.0;
  for (const Eigen::Vector3d& x : model.points()) {
    sum += ((estimate.R * x + estimate.t) - (truth.R * x + truth.t)).norm();
  }
  return sum / static_cast<double>(model.points().size());
}

double adds_error(const PoseErrorModel& model, const Pose& estimate, const Pose& truth) {
  // The nearest vertex at the estimated pose, found in the model frame: the tree is
  // built once, each true-pose vertex is taken back through the estimated pose.
  const Eigen::Matrix3d back = estimate.R.inverse();
  double sum = 0.0;
  for (const Eigen::Vector3d& x : model.points()) {
    const Eigen::Vector3d in_estimate_frame = back * (truth.R * x + truth.t - estimate.t);
    sum += model.nearest_vertex_distance(in_estimate_frame);
  }
  return sum / static_cast<double>(model.points().size());
}

double add_or_adds_error(const PoseErrorModel& model, const Pose& estimate, const Pose& truth) {
  return model.symmetric() ? adds_error(model, estimate, truth) : add_error(model, estimate, truth);
}

double mssd_error(const PoseErrorModel& model, const Pose& estimate, const Pose& truth) {
  // |R_e x + t_e - R_g (S x) - t_g| = |y - S x| with y = R_g^T (R_e x + t_e - t_g): the
  // estimate is carried into the truth's model frame once, then each symmetry is a
  // cheap comparison there. A symmetry stops as soon as its maximum passes the best one.
  const Eigen::Matrix3d back = truth.R.transpose();
  const std::vector<Eigen::Vector3d>& points = model.points();
  std::vector<Eigen::Vector3d> y(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) y[i] = back * (estimate.R * points[i] + estimate.t - truth.t);
  double best = std::numeric_limits<double>::infinity();
  for (const SymmetryTransform& s : model.symmetries()) {
    double worst = 0.0;
    for (std::size_t i = 0; i < points.size() && worst < best; ++i) {
      worst = std::max(worst, (y[i] - (s.R * points[i] + s.t)).squaredNorm());
    }
    best = std::min(best, worst);
  }
  return std::sqrt(best);
}

double mspd_error(const PoseErrorModel& model, const Pose& estimate, const Pose& truth,
                  const Eigen::Matrix3d& K) {
  const std::vector<Eigen::Vector3d>& points = model.points();
  std::vector<Eigen::Vector2d> at_estimate(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) at_estimate[i] = project(K, estimate.R * points[i] + estimate.t);
  double best = std::numeric_limits<double>::infinity();
  for (const SymmetryTransform& s : model.symmetries()) {
    const Eigen::Matrix3d R = truth.R * s.R;
    const Eigen::Vector3d t = truth.R * s.t + truth.t;
    double worst = 0.0;
    for (std::size_t i = 0; i < points.size() && worst < best; ++i) {
      worst = std::max(worst, (project(K, R * points[i] + t) - at_estimate[i]).squaredNorm());
    }
    best = std::min(best, worst);
  }
  return std::sqrt(best);
}

std::vector<double> bop_fraction_thresholds() {
  std::vector<double> thresholds;
  for (int i = 0; i < 10; ++i) thresholds.push_back(0.05 + i * 0.05);
  return thresholds;
}

ModelDepthRenderer::ModelDepthRenderer(std::shared_ptr<const Mesh> mesh) {
  const int index = scene_.add_mesh(std::move(mesh));
  instance_ = scene_.add_instance(index, Pose{});
}

cv::Mat ModelDepthRenderer::depth(const Pose& pose, const PinholeCamera& camera) {
  scene_.set_pose(instance_, pose);
  scene_.commit();
  RaycastOptions options;
  options.areas = {projected_area(scene_.mesh(0), pose, camera)};
  return raycast(scene_, camera, options).depth;
}

std::vector<double> vsd_errors(const cv::Mat& depth_test, const cv::Mat& depth_estimate,
                               const cv::Mat& depth_truth, const Eigen::Matrix3d& K, double diameter,
                               const VsdSettings& settings) {
  if (depth_test.type() != CV_32FC1 || depth_estimate.type() != CV_32FC1 || depth_truth.type() != CV_32FC1 ||
      depth_test.size() != depth_estimate.size() || depth_test.size() != depth_truth.size()) {
    throw std::invalid_argument("vsd_errors: three CV_32FC1 depth images of one size expected");
  }
  const double fx = K(0, 0), fy = K(1, 1), cx = K(0, 2), cy = K(1, 2);
  const double delta = settings.delta_mm;
  long union_count = 0, intersection_count = 0;
  std::vector<double> distances;  // |dist_gt - dist_est| / diameter over the intersection
  for (int v = 0; v < depth_test.rows; ++v) {
    const float* test = depth_test.ptr<float>(v);
    const float* est = depth_estimate.ptr<float>(v);
    const float* gt = depth_truth.ptr<float>(v);
    const double ry = (v - cy) / fy;
    for (int u = 0; u < depth_test.cols; ++u) {
      if (est[u] <= 0 && gt[u] <= 0) continue;  // neither part there: in no mask
      // Depth to distance from the camera centre (misc.depth_im_to_dist_im_fast).
      const double rx = (u - cx) / fx;
      const double scale = std::sqrt(rx * rx + ry * ry + 1.0);
      const double d_test = test[u] * scale, d_est = est[u] * scale, d_gt = gt[u] * scale;
      const bool visible_gt = gt[u] > 0 && (d_gt - d_test <= delta || test[u] == 0);
      const bool visible_est = (est[u] > 0 && (d_est - d_test <= delta || test[u] == 0)) ||
                               (visible_gt && est[u] > 0);
      if (!visible_gt && !visible_est) continue;
      ++union_count;
      if (visible_gt && visible_est) {
        ++intersection_count;
        distances.push_back(std::abs(d_gt - d_est) / diameter);
      }
    }
  }
  std::vector<double> errors;
  for (double tau : settings.taus) {
    if (union_count == 0) {
      errors.push_back(1.0);
      continue;
    }
    long misaligned = 0;
    for (double d : distances) misaligned += d >= tau;
    errors.push_back(static_cast<double>(misaligned + union_count - intersection_count) /
                     static_cast<double>(union_count));
  }
  return errors;
}

}  // namespace flexsight

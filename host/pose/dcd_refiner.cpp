#include "host/pose/dcd_refiner.h"

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <cmath>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

double value_of(double x) { return x; }
template <int N>
double value_of(const ceres::Jet<double, N>& x) {
  return x.a;
}

// The tensor read at (u, v): its value, and for Ceres's Jets the chain rule through the
// bilinear interpolation's derivatives.
double lookup(const DcdTensor& tensor, double u, double v, int bin) { return tensor.sample(u, v, bin); }
template <int N>
ceres::Jet<double, N> lookup(const DcdTensor& tensor, const ceres::Jet<double, N>& u,
                             const ceres::Jet<double, N>& v, int bin) {
  double du = 0.0, dv = 0.0;
  const double value = tensor.sample(u.a, v.a, bin, &du, &dv);
  return ceres::Jet<double, N>(value, du * u.v + dv * v.v);
}

// One edge point: the chamfer distance where the pose projects it, in the layer of the
// direction the pose projects its tangent to (taken as constant within a step).
struct EdgePointResidual {
  EdgePointResidual(const Eigen::Vector3f& point, const Eigen::Vector3f& tangent,
                    const PinholeCamera& camera, const DcdTensor& tensor, cv::Point origin)
      : point_(point.cast<double>()), tangent_(tangent.cast<double>()), camera_(camera),
        tensor_(tensor), origin_(origin) {}

  template <typename T>
  bool operator()(const T* rotation, const T* translation, T* residual) const {
    const T model[3] = {T(point_.x()), T(point_.y()), T(point_.z())};
    T p[3];
    ceres::AngleAxisRotatePoint(rotation, model, p);
    p[0] += translation[0];
    p[1] += translation[1];
    p[2] += translation[2];
    if (value_of(p[2]) <= 1e-6) {
      residual[0] = T(tensor_.sample(-1e9, -1e9, 0));
      return true;
    }
    const T u = T(camera_.fx) * p[0] / p[2] + T(camera_.cx - origin_.x);
    const T v = T(camera_.fy) * p[1] / p[2] + T(camera_.cy - origin_.y);

    const double w[3] = {value_of(rotation[0]), value_of(rotation[1]), value_of(rotation[2])};
    const double t_model[3] = {tangent_.x(), tangent_.y(), tangent_.z()};
    double t_cam[3];
    ceres::AngleAxisRotatePoint(w, t_model, t_cam);
    const double px = value_of(p[0]), py = value_of(p[1]), pz = value_of(p[2]);
    const double du = camera_.fx * (t_cam[0] * pz - px * t_cam[2]);
    const double dv = camera_.fy * (t_cam[1] * pz - py * t_cam[2]);
    residual[0] = lookup(tensor_, u, v, tensor_.bin_of(std::atan2(dv, du)));
    return true;
  }

  Eigen::Vector3d point_, tangent_;
  const PinholeCamera& camera_;
  const DcdTensor& tensor_;
  cv::Point origin_;
};

}  // namespace

void DcdRefineParams::check() const {
  if (max_iterations < 0 || max_iterations > 10000) {
    throw InputError("refine parameter max_iterations", "must be in 0..10000");
  }
  if (!(huber_pixels > 0.0)) throw InputError("refine parameter huber_pixels", "must be positive");
}

double mean_chamfer(const std::vector<Eigen::Vector3f>& points,
                    const std::vector<Eigen::Vector3f>& tangents, const Pose& pose,
                    const PinholeCamera& camera, const DcdTensor& tensor, cv::Point tensor_origin) {
  if (points.empty()) return tensor.sample(-1e9, -1e9, 0);
  double rotation[3];
  ceres::RotationMatrixToAngleAxis(ceres::ColumnMajorAdapter3x3(pose.R.data()), rotation);
  double sum = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    EdgePointResidual residual(points[i], tangents[i], camera, tensor, tensor_origin);
    double value = 0.0;
    residual(rotation, pose.t.data(), &value);
    sum += value;
  }
  return sum / static_cast<double>(points.size());
}

DcdRefineResult refine_on_dcd(const std::vector<Eigen::Vector3f>& points,
                              const std::vector<Eigen::Vector3f>& tangents, const Pose& initial,
                              const PinholeCamera& camera, const DcdTensor& tensor,
                              cv::Point tensor_origin, const DcdRefineParams& params) {
  params.check();
  DcdRefineResult result;
  result.pose = initial;
  result.initial_cost = mean_chamfer(points, tangents, initial, camera, tensor, tensor_origin);
  result.final_cost = result.initial_cost;
  if (points.empty() || params.max_iterations == 0) return result;

  double rotation[3];
  ceres::RotationMatrixToAngleAxis(ceres::ColumnMajorAdapter3x3(initial.R.data()), rotation);
  double translation[3] = {initial.t.x(), initial.t.y(), initial.t.z()};
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  ceres::HuberLoss loss(params.huber_pixels);
  for (std::size_t i = 0; i < points.size(); ++i) {
    auto* cost = new ceres::AutoDiffCostFunction<EdgePointResidual, 1, 3, 3>(
        new EdgePointResidual(points[i], tangents[i], camera, tensor, tensor_origin));
    problem.AddResidualBlock(cost, &loss, rotation, translation);
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = params.max_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  ceres::AngleAxisToRotationMatrix(rotation, ceres::ColumnMajorAdapter3x3(result.pose.R.data()));
  result.pose.t = Eigen::Vector3d(translation[0], translation[1], translation[2]);
  result.iterations = static_cast<int>(summary.iterations.size());
  result.final_cost = mean_chamfer(points, tangents, result.pose, camera, tensor, tensor_origin);
  return result;
}

}  // namespace flexsight

#include "host/pose/pose_estimator.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The camera that sees only `region` of `camera`'s image (same rays, pixel (0, 0) at the
// region's corner): renders of a box cost the box's pixels, not the image's.
PinholeCamera crop_camera(const PinholeCamera& camera, const cv::Rect& region) {
  PinholeCamera cropped = camera;
  cropped.cx -= region.x;
  cropped.cy -= region.y;
  cropped.width = region.width;
  cropped.height = region.height;
  return cropped;
}

cv::Rect grow(const cv::Rect& box, double fraction, const cv::Size& image) {
  const int dx = static_cast<int>(std::ceil(fraction * box.width));
  const int dy = static_cast<int>(std::ceil(fraction * box.height));
  return cv::Rect(box.x - dx, box.y - dy, box.width + 2 * dx, box.height + 2 * dy) & cv::Rect(cv::Point(), image);
}

// Depth pixels of `region` as camera-frame points, strided to at most `max_points`.
std::vector<Eigen::Vector3f> scene_points(const cv::Mat& depth, const cv::Rect& region,
                                          const PinholeCamera& camera, int max_points) {
  int valid = 0;
  for (int y = region.y; y < region.br().y; ++y) {
    for (int x = region.x; x < region.br().x; ++x) valid += depth.at<float>(y, x) > 0.0f;
  }
  const int stride = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(valid) / max_points))));
  std::vector<Eigen::Vector3f> points;
  for (int y = region.y; y < region.br().y; y += stride) {
    for (int x = region.x; x < region.br().x; x += stride) {
      const float z = depth.at<float>(y, x);
      if (!(z > 0.0f)) continue;
      points.emplace_back(static_cast<float>((x - camera.cx) / camera.fx * z),
                          static_cast<float>((y - camera.cy) / camera.fy * z), z);
    }
  }
  return points;
}

// The model, box and images estimate() takes: anything else is refused before any work.
void check_estimate_inputs(const PoseModel& model, const cv::Mat& image, const cv::Mat& depth,
                           const cv::Rect& box) {
  if (!model.mesh || !model.templates) throw std::invalid_argument("PoseEstimator: model without mesh or templates");
  if (box.width <= 0 || box.height <= 0) throw InputError("box", "is empty");
  const cv::Rect image_rect(cv::Point(), image.size());
  if ((box & image_rect) != box) {
    throw InputError("box", "(" + std::to_string(box.x) + ", " + std::to_string(box.y) + ", " +
                                std::to_string(box.width) + " x " + std::to_string(box.height) +
                                ") is not inside the " + std::to_string(image.cols) + " x " +
                                std::to_string(image.rows) + " image");
  }
  if (depth.size() != image.size() || depth.type() != CV_32FC1) {
    throw InputError("depth", "must be a float image of the image's size (" + std::to_string(image.cols) +
                                  " x " + std::to_string(image.rows) + ")");
  }
}

// Pixels measured well in front of the part's surface belong to something that hides it;
// a hidden part may reach as far as the largest template the search allows
// (max_area_ratio times the box). Their points' costs in `tensor` are capped.
void cap_occluded_points(DcdTensor& tensor, const PoseModel& model, const cv::Mat& depth,
                         const cv::Rect& box, const cv::Rect& region, double surface_depth,
                         const PoseEstimatorParams& params) {
  const cv::Rect reach = grow(box, std::sqrt(params.search.max_area_ratio), depth.size());
  const cv::Mat nearer = depth(reach) < surface_depth - params.occluder_margin * model.mesh->diameter;
  const cv::Mat hidden = nearer & (depth(reach) > 0.0f);
  tensor.cap(hidden, reach.tl() - region.tl(), static_cast<float>(params.occluded_point_cost));
}

// A candidate after its refinement on the edges, with the template view it came from.
struct RefinedCandidate {
  Pose pose;
  double edge_cost;
  const EdgeView* view;
};

// Every candidate refined on the edges (unless the refinement is on the depth only), the
// best edge fit first; the time it took is added to `refine_ms`.
std::vector<RefinedCandidate> refine_candidates(const PoseModel& model,
                                                const std::vector<PoseCandidate>& candidates,
                                                const PinholeCamera& camera, const DcdTensor& tensor,
                                                const cv::Rect& region,
                                                const PoseEstimatorParams& params, double& refine_ms) {
  std::vector<RefinedCandidate> refined;
  for (const PoseCandidate& candidate : candidates) {
    const EdgeView& view = model.templates->views[candidate.view];
    const Clock::time_point start = Clock::now();
    RefinedCandidate r{candidate.pose, candidate.cost, &view};
    if (params.refinement != PoseRefinement::kDepthOnly) {
      const DcdRefineResult result = refine_on_dcd(view.points, view.tangents, candidate.pose, camera, tensor,
                                                   region.tl(), params.refine);
      r.pose = result.pose;
      r.edge_cost = result.final_cost;
    }
    refine_ms += ms_since(start);
    refined.push_back(r);
  }
  std::stable_sort(refined.begin(), refined.end(), [](const RefinedCandidate& a, const RefinedCandidate& b) {
    return a.edge_cost < b.edge_cost;
  });
  return refined;
}

// Half turns of a candidate about the model's axes join it: edges and a depth surface
// seen from one side often fit a part and its turned twin about equally, and only the
// complete fit (ICP, then the score) tells them apart.
std::vector<RefinedCandidate> with_half_turns(const RefinedCandidate& r, const PoseModel& model,
                                              const PoseEstimatorParams& params) {
  std::vector<RefinedCandidate> out{r};
  if (!params.try_half_turns || params.refinement == PoseRefinement::kEdgesOnly) return out;
  const Eigen::Vector3d centre = model.mesh->bounds.center().cast<double>();
  for (int axis = 0; axis < 3; ++axis) {
    RefinedCandidate turned = r;
    const Eigen::Matrix3d half = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
    // Turn about the axis through the box centre, which stays where it was.
    turned.pose.R = r.pose.R * half;
    turned.pose.t = r.pose.t + r.pose.R * (centre - half * centre);
    out.push_back(turned);
  }
  return out;
}

}  // namespace

void PoseEstimatorParams::check() const {
  dcd.check();
  search.check();
  refine.check();
  icp.check();
  if (!(box_margin >= 0.0 && box_margin <= 2.0)) throw InputError("pose parameter box_margin", "must be in [0, 2]");
  if (max_scene_points < 10) throw InputError("pose parameter max_scene_points", "must be at least 10");
  if (scored_candidates < 1) throw InputError("pose parameter scored_candidates", "must be at least 1");
  if (!(retry_below_score >= 0.0 && retry_below_score <= 1.0)) {
    throw InputError("pose parameter retry_below_score", "must be in [0, 1]");
  }
  if (max_model_points < 10) throw InputError("pose parameter max_model_points", "must be at least 10");
  if (!(depth_tolerance > 0.0)) throw InputError("pose parameter depth_tolerance", "must be positive");
  if (!(occluder_margin >= 0.0 && occluder_margin <= 10.0)) {
    throw InputError("pose parameter occluder_margin", "must be in [0, 10] diameters (0 = off)");
  }
  if (!(occluded_point_cost >= 0.0 && occluded_point_cost <= dcd.max_distance)) {
    throw InputError("pose parameter occluded_point_cost", "must be in [0, the tensor's max_distance]");
  }
}

double box_surface_depth(const cv::Mat& depth, const cv::Rect& box) {
  auto median_in = [&](const cv::Rect& r) {
    std::vector<float> values;
    for (int y = r.y; y < r.br().y; ++y) {
      for (int x = r.x; x < r.br().x; ++x) {
        const float z = depth.at<float>(y, x);
        if (z > 0.0f) values.push_back(z);
      }
    }
    if (values.empty()) return 0.0;
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return static_cast<double>(values[values.size() / 2]);
  };
  const cv::Rect middle(box.x + box.width / 4, box.y + box.height / 4, std::max(1, box.width / 2),
                        std::max(1, box.height / 2));
  const double depth_in_middle = median_in(middle & box);
  return depth_in_middle > 0.0 ? depth_in_middle : median_in(box);
}

struct PoseEstimator::Impl {
  PoseEstimatorParams params;
  // One render scene per mesh (a single instance moved from pose to pose).
  std::map<const Mesh*, RenderScene> scenes;

  RenderScene& scene_of(const PoseModel& model) {
    auto it = scenes.find(model.mesh.get());
    if (it == scenes.end()) {
      RenderScene scene;
      const int mesh = scene.add_mesh(model.mesh);
      scene.add_instance(mesh, Pose{});
      it = scenes.emplace(model.mesh.get(), std::move(scene)).first;
    }
    return it->second;
  }

  RaycastImages render(const PoseModel& model, const Pose& pose, const PinholeCamera& region_camera) {
    RenderScene& scene = scene_of(model);
    scene.set_pose(0, pose);
    scene.commit();
    RaycastOptions options;
    options.threads = 1;
    return raycast(scene, region_camera, options);
  }

  // Fraction of the part's rendered pixels with a measured depth that agree with it;
  // pixels where the measurement is nearer (an occluder) do not count either way.
  double depth_fit(const RaycastImages& rendered, const cv::Mat& depth, const cv::Rect& region,
                   double tolerance) const {
    int agree = 0, disagree = 0;
    for (int y = 0; y < region.height; ++y) {
      for (int x = 0; x < region.width; ++x) {
        const float model_z = rendered.depth.at<float>(y, x);
        const float scene_z = depth.at<float>(y + region.y, x + region.x);
        if (!(model_z > 0.0f) || !(scene_z > 0.0f)) continue;
        const double difference = scene_z - model_z;
        if (std::abs(difference) <= tolerance) {
          ++agree;
        } else if (difference > tolerance) {
          ++disagree;  // the measured surface lies behind the part: the part is not there
        }
      }
    }
    return agree + disagree == 0 ? 0.0 : static_cast<double>(agree) / (agree + disagree);
  }

  Pose run_icp(const PoseModel& model, const Pose& pose, const RaycastImages& rendered,
               const std::vector<Eigen::Vector3f>& scene) {
    std::vector<Eigen::Vector3f> points, normals;
    const Eigen::Matrix3f to_model = pose.R.transpose().cast<float>();
    const Eigen::Vector3f t = pose.t.cast<float>();
    int visible = cv::countNonZero(rendered.depth > 0.0f);
    const int stride = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(visible) / params.max_model_points))));
    for (int y = 0; y < rendered.depth.rows; y += stride) {
      for (int x = 0; x < rendered.depth.cols; x += stride) {
        if (!(rendered.depth.at<float>(y, x) > 0.0f)) continue;
        const cv::Vec3f p = rendered.point.at<cv::Vec3f>(y, x);
        const cv::Vec3f n = rendered.geometric_normal.at<cv::Vec3f>(y, x);
        points.push_back(to_model * (Eigen::Vector3f(p[0], p[1], p[2]) - t));
        normals.push_back(to_model * Eigen::Vector3f(n[0], n[1], n[2]));
      }
    }
    if (points.size() < 10 || scene.size() < 10) return pose;
    PointToPlaneIcp icp(std::move(points), std::move(normals));
    IcpParams icp_params = params.icp;
    icp_params.max_distance_mm = std::max(icp_params.max_distance_mm, 0.1 * model.mesh->diameter);
    const IcpResult result = icp.refine(scene, pose, icp_params);
    return result.inliers >= 10 ? result.pose : pose;
  }
};

PoseEstimator::PoseEstimator(const PoseEstimatorParams& params) : impl_(std::make_unique<Impl>()) {
  params.check();
  impl_->params = params;
}
PoseEstimator::~PoseEstimator() = default;

PoseEstimate PoseEstimator::estimate(const PoseModel& model, const cv::Mat& image, const cv::Mat& depth,
                                     const PinholeCamera& camera, const cv::Rect& box) {
  const PoseEstimatorParams& params = impl_->params;
  check_estimate_inputs(model, image, depth, box);
  PoseEstimate estimate;
  estimate.obj_id = model.obj_id;

  auto start = Clock::now();
  const cv::Rect region = grow(box, params.box_margin, image.size());
  const double surface_depth = box_surface_depth(depth, box);
  if (!(surface_depth > 0.0)) throw InputError("depth", "has no measured pixel in the box");
  DcdTensor tensor(detect_edges(image, region, params.dcd), params.dcd);
  if (params.occluder_margin > 0.0) {
    cap_occluded_points(tensor, model, depth, box, region, surface_depth, params);
  }
  estimate.times.edges_ms = ms_since(start);

  start = Clock::now();
  const std::vector<PoseCandidate> candidates =
      search_templates(*model.templates, model.in_plane_steps, tensor, region.tl(), camera, box,
                       surface_depth, params.search);
  estimate.times.search_ms = ms_since(start);
  estimate.candidates = static_cast<int>(candidates.size());

  const PinholeCamera region_camera = crop_camera(camera, region);
  const std::vector<Eigen::Vector3f> scene = scene_points(depth, box, camera, params.max_scene_points);
  const double tolerance = std::max(2.0, params.depth_tolerance * model.mesh->diameter);
  const double far = params.dcd.max_distance;
  // Every candidate refined on the edges; the best few by edge fit then fitted to the
  // depth and scored (ICP and the renders cost more than the refinement).
  const std::vector<RefinedCandidate> refined =
      refine_candidates(model, candidates, camera, tensor, region, params, estimate.times.refine_ms);
  bool first = true;
  auto fit_and_score = [&](const RefinedCandidate& r) {
    Pose pose = r.pose;
    start = Clock::now();
    if (params.refinement != PoseRefinement::kEdgesOnly) {
      pose = impl_->run_icp(model, pose, impl_->render(model, pose, region_camera), scene);
    }
    estimate.times.icp_ms += ms_since(start);

    start = Clock::now();
    const double edge_cost = mean_chamfer(r.view->points, r.view->tangents, pose, camera, tensor, region.tl());
    const double fit = impl_->depth_fit(impl_->render(model, pose, region_camera), depth, region, tolerance);
    const double score = fit * std::max(0.0, 1.0 - edge_cost / far);
    estimate.times.score_ms += ms_since(start);
    if (first || score > estimate.score) {
      estimate.pose = pose;
      estimate.score = score;
      estimate.edge_cost = edge_cost;
      estimate.depth_fit = fit;
      first = false;
    }
  };
  // The best few candidates by edge fit are fitted to the depth and scored; when none
  // scores well, the rest of them too (a part seen from an ambiguous side: the cost
  // falls on the hard parts only).
  const std::size_t scored = std::min<std::size_t>(refined.size(), params.scored_candidates);
  for (std::size_t i = 0; i < refined.size(); ++i) {
    if (i >= scored && estimate.score >= params.retry_below_score) break;
    for (const RefinedCandidate& r : with_half_turns(refined[i], model, params)) fit_and_score(r);
  }
  return estimate;
}

}  // namespace flexsight

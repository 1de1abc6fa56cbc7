#include "host/pose/edge_template.h"

#include <omp.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "host/io/input_error.h"
#include "host/pose/view_sphere.h"
#include "host/render/raycaster.h"

namespace flexsight {
namespace {

// The part is rendered this many diameters away: far enough that the perspective of the
// template is close to that of a part in a bin, near enough to keep it sharp.
constexpr double kDistanceInDiameters = 3.0;
// Fraction of the template image the part's diameter spans.
constexpr double kSpan = 0.7;
// Half size of the window whose edge pixels give an edge point's direction.
constexpr int kTangentRadius = 3;

struct EdgePixel {
  int x, y;
};

// Object pixels on the occluding contour (a 4-neighbour is background, or much farther:
// the part hides itself there) or on a crease (the surface normal turns by more than
// the crease angle towards a neighbour on the same surface).
std::vector<EdgePixel> find_edge_pixels(const RaycastImages& images, double depth_jump,
                                        double crease_cosine) {
  const int width = images.depth.cols, height = images.depth.rows;
  std::vector<EdgePixel> edges;
  auto is_part = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < width && y < height && images.instance.at<int>(y, x) >= 0;
  };
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!is_part(x, y)) continue;
      const float depth = images.depth.at<float>(y, x);
      const cv::Vec3f normal = images.geometric_normal.at<cv::Vec3f>(y, x);
      bool edge = false;
      for (int k = 0; k < 4 && !edge; ++k) {
        const int nx = x + dx[k], ny = y + dy[k];
        if (!is_part(nx, ny)) {
          edge = true;
          break;
        }
        const float neighbour_depth = images.depth.at<float>(ny, nx);
        if (neighbour_depth - depth > depth_jump) {
          edge = true;
        } else if (k % 2 == 0 && std::abs(neighbour_depth - depth) <= depth_jump) {
          // Creases are looked for towards the right and down neighbours only, so each
          // crease is marked once, on one side.
          if (normal.dot(images.geometric_normal.at<cv::Vec3f>(ny, nx)) < crease_cosine) {
            edge = true;
          }
        }
      }
      if (edge) edges.push_back({x, y});
    }
  }
  return edges;
}

// The direction of the edge through pixel i: the main axis of the edge pixels around it.
Eigen::Vector2d edge_direction(const std::vector<EdgePixel>& edges, const cv::Mat& edge_index,
                               int i) {
  const int x0 = edges[i].x, y0 = edges[i].y;
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  int count = 0;
  for (int y = std::max(0, y0 - kTangentRadius); y <= std::min(edge_index.rows - 1, y0 + kTangentRadius); ++y) {
    for (int x = std::max(0, x0 - kTangentRadius); x <= std::min(edge_index.cols - 1, x0 + kTangentRadius); ++x) {
      if (edge_index.at<int>(y, x) < 0) continue;
      const Eigen::Vector2d p(x - x0, y - y0);
      mean += p;
      scatter += p * p.transpose();
      ++count;
    }
  }
  mean /= count;
  scatter = scatter / count - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(scatter);
  return solver.eigenvectors().col(1);  // the larger eigenvalue's vector
}

// Indices of up to n edge pixels in farthest-point order, starting from the first in
// raster order: each next pixel is the one farthest from those already taken.
std::vector<int> farthest_point_order(const std::vector<EdgePixel>& edges, int n) {
  std::vector<int> order;
  if (edges.empty()) return order;
  std::vector<double> distance(edges.size(), std::numeric_limits<double>::max());
  int next = 0;
  while (static_cast<int>(order.size()) < n) {
    order.push_back(next);
    double best = -1.0;
    int best_index = -1;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const double ddx = edges[i].x - edges[next].x, ddy = edges[i].y - edges[next].y;
      distance[i] = std::min(distance[i], ddx * ddx + ddy * ddy);
      if (distance[i] > best) {
        best = distance[i];
        best_index = static_cast<int>(i);
      }
    }
    if (best <= 0.0) break;  // every pixel taken
    next = best_index;
  }
  return order;
}

EdgeView make_view(const RenderScene& scene, const PinholeCamera& camera, const Pose& pose,
                   double diameter, const TemplateParams& params) {
  RaycastOptions options;
  options.threads = 1;
  const RaycastImages images = raycast(scene, camera, options);

  const double depth_jump = std::max(1.0, 0.02 * diameter);
  const double crease_cosine = std::cos(params.crease_degrees * M_PI / 180.0);
  const std::vector<EdgePixel> edges = find_edge_pixels(images, depth_jump, crease_cosine);
  cv::Mat edge_index(camera.height, camera.width, CV_32SC1, cv::Scalar(-1));
  for (std::size_t i = 0; i < edges.size(); ++i) edge_index.at<int>(edges[i].y, edges[i].x) = static_cast<int>(i);

  EdgeView view;
  view.rotation = pose.R;
  const Eigen::Matrix3f to_model = pose.R.transpose().cast<float>();
  const Eigen::Vector3f origin = pose.t.cast<float>();
  for (int i : farthest_point_order(edges, params.points_per_view)) {
    const cv::Vec3f p = images.point.at<cv::Vec3f>(edges[i].y, edges[i].x);
    const Eigen::Vector2d direction = edge_direction(edges, edge_index, i);
    // The edge runs across the image at the point's depth: its direction in the camera
    // frame has no z component (exact for edges parallel to the image plane, and the
    // projection of any edge direction onto the image is all the matcher uses).
    const Eigen::Vector3f tangent_camera(static_cast<float>(direction.x()),
                                         static_cast<float>(direction.y()), 0.0f);
    view.points.push_back(to_model * (Eigen::Vector3f(p[0], p[1], p[2]) - origin));
    view.tangents.push_back((to_model * tangent_camera).normalized());
  }

  std::vector<float> depths;
  for (int y = 0; y < images.depth.rows; ++y) {
    for (int x = 0; x < images.depth.cols; ++x) {
      const float depth = images.depth.at<float>(y, x);
      if (depth > 0.0f) depths.push_back(depth);
    }
  }
  if (!depths.empty()) {
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    view.surface_depth_offset = depths[depths.size() / 2] - static_cast<float>(pose.t.z());
  }
  return view;
}

}  // namespace

void TemplateParams::check() const {
  auto require = [](bool ok, const char* field, const char* what) {
    if (!ok) throw InputError(std::string("template parameter ") + field, what);
  };
  require(views >= 1 && views <= 100000, "views", "must be in 1..100000");
  // The search keeps candidates 12 degrees apart and the refinement turns them further;
  // steps finer than 1 degree only multiply its time.
  require(in_plane_steps >= 1 && in_plane_steps <= 360, "in_plane_steps", "must be in 1..360");
  require(points_per_view >= 4 && points_per_view <= 4096, "points_per_view", "must be in 4..4096");
  require(crease_degrees > 0.0f && crease_degrees < 180.0f, "crease_degrees",
          "must be in (0, 180) degrees");
  require(render_size >= 32 && render_size <= 4096, "render_size", "must be in 32..4096 pixels");
}

const PartTemplates* TemplateSet::find(int obj_id) const {
  for (const auto& part : parts) {
    if (part.obj_id == obj_id) return &part;
  }
  return nullptr;
}

PartTemplates make_part_templates(const Mesh& mesh, int obj_id, const std::string& name,
                                  const TemplateParams& params, int threads) {
  params.check();
  PartTemplates part;
  part.obj_id = obj_id;
  part.name = name;
  part.diameter = mesh.diameter;

  // Render about the centre of the bounding box so the part stays in the image, then
  // store everything relative to the model's own origin.
  const Eigen::Vector3d centre = mesh.bounds.center().cast<double>();
  const double distance = kDistanceInDiameters * mesh.diameter;
  const PinholeCamera camera = centred_camera(params.render_size, params.render_size,
                                              kSpan * params.render_size * kDistanceInDiameters);

  const std::vector<Eigen::Vector3d> directions = fibonacci_sphere(params.views);
  part.views.resize(directions.size());
  auto shared_mesh = std::make_shared<const Mesh>(mesh);
  const int thread_count = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel num_threads(thread_count)
  {
    RenderScene scene;  // one per thread: instances move from view to view
    const int mesh_index = scene.add_mesh(shared_mesh);
    const int instance = scene.add_instance(mesh_index, Pose{});
#pragma omp for schedule(dynamic)
    for (int v = 0; v < static_cast<int>(directions.size()); ++v) {
      Pose pose;
      pose.R = look_at_origin(directions[v]);
      pose.t = Eigen::Vector3d(0.0, 0.0, distance) - pose.R * centre;
      scene.set_pose(instance, pose);
      scene.commit();
      part.views[v] = make_view(scene, camera, pose, mesh.diameter, params);
    }
  }
  return part;
}

}  // namespace flexsight

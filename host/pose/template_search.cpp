#include "host/pose/template_search.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

// A view projected with its origin on the optical axis at one depth, in normalised
// image coordinates (x / z, y / z): a turn about the optical axis turns these exactly,
// so each in-plane rotation of the view is a 2D rotation of one projection.
struct ProjectedView {
  std::vector<Eigen::Vector2d> normalised;  // every point of the view
  std::vector<double> angles;               // edge direction of the first coarse points,
                                            // radians in normalised coordinates
  std::vector<Eigen::Vector2d> directions;  // the same directions as unit vectors
};

ProjectedView project_view(const EdgeView& view, double depth, int coarse_points) {
  ProjectedView out;
  const int n = static_cast<int>(view.points.size());
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = view.rotation * view.points[i].cast<double>();
    const double z = p.z() + depth;
    if (z <= 1e-6) continue;
    out.normalised.emplace_back(p.x() / z, p.y() / z);
    if (static_cast<int>(out.angles.size()) >= coarse_points) continue;
    // The projected edge direction: the derivative of the projection along the tangent.
    const Eigen::Vector3d tangent = view.rotation * view.tangents[i].cast<double>();
    const Eigen::Vector2d direction(tangent.x() * z - p.x() * tangent.z(), tangent.y() * z - p.y() * tangent.z());
    out.angles.push_back(std::atan2(direction.y(), direction.x()));
    out.directions.push_back(direction.normalized());
  }
  return out;
}

// A template at one view and in-plane rotation, projected with its origin on the
// optical axis: its coarse points' offsets from the origin's pixel (pixels) and their
// orientation bins.
struct ProjectedTemplate {
  std::vector<Eigen::Vector2d> offsets;
  std::vector<int> bins;
  Eigen::AlignedBox2d bounds;  // of all the view's points
};

// `view` turned by `angle` about the optical axis. With square pixels the turn adds
// `angle` to every edge direction; otherwise the direction is measured in pixels.
ProjectedTemplate turn_view(const ProjectedView& view, double angle, const PinholeCamera& camera,
                            const DcdTensor& tensor) {
  ProjectedTemplate out;
  const double c = std::cos(angle), s = std::sin(angle);
  const bool square = camera.fx == camera.fy;
  for (std::size_t i = 0; i < view.normalised.size(); ++i) {
    const Eigen::Vector2d& q = view.normalised[i];
    const Eigen::Vector2d offset(camera.fx * (c * q.x() - s * q.y()), camera.fy * (s * q.x() + c * q.y()));
    out.bounds.extend(offset);
    if (i >= view.angles.size()) continue;
    out.offsets.push_back(offset);
    if (square) {
      out.bins.push_back(tensor.bin_of(view.angles[i] + angle));
    } else {
      const Eigen::Vector2d& d = view.directions[i];
      out.bins.push_back(tensor.bin_of(std::atan2(camera.fy * (s * d.x() + c * d.y()), camera.fx * (c * d.x() - s * d.y()))));
    }
  }
  return out;
}

// The tensor as bytes (distance x 8, saturated), layer after layer: the search reads it
// at random places millions of times, and a quarter of the float tensor's size stays
// in the cache (the float tensor's lookups were a large share of the search's time;
// docs/tuning-log.md).
class CompactTensor {
 public:
  explicit CompactTensor(const DcdTensor& tensor)
      : tensor_(tensor), width_(tensor.width()), height_(tensor.height()), bins_(tensor.bins()),
        cells_(static_cast<std::size_t>(width_) * height_ * bins_) {
    for (int b = 0; b < bins_; ++b) {
      cv::Mat bytes(height_, width_, CV_8UC1, cells_.data() + static_cast<std::size_t>(b) * width_ * height_);
      tensor.layer(b).convertTo(bytes, CV_8UC1, kScale);  // saturates at 255
    }
  }
  // Sum of the cells under points `offsets` moved by (u0, v0) minus the tensor's origin,
  // in units of 1/kScale pixel; stops early once the sum exceeds `give_up`.
  int sum(const std::vector<Eigen::Vector2d>& offsets, const std::vector<int>& bins, double u0,
          double v0, int give_up) const {
    int total = 0;
    for (std::size_t i = 0; i < offsets.size(); ++i) {
      const int x = static_cast<int>(std::floor(u0 + offsets[i].x() + 0.5));
      const int y = static_cast<int>(std::floor(v0 + offsets[i].y() + 0.5));
      if (x < 0 || y < 0 || x >= width_ || y >= height_) {
        total += static_cast<int>(std::min(255.0, tensor_.outside_cost(x, y) * kScale));
      } else {
        total += cells_[(static_cast<std::size_t>(bins[i]) * height_ + y) * width_ + x];
      }
      if (total > give_up) break;
    }
    return total;
  }
  static constexpr double kScale = 8.0;

 private:
  const DcdTensor& tensor_;
  int width_, height_, bins_;
  std::vector<std::uint8_t> cells_;
};

// The mean chamfer distance (pixels) of template `t` with its origin at (u0, v0) image
// pixels; above `bound` (pixels) it may stop early and return a value above `bound`.
double mean_cost(const ProjectedTemplate& t, double u0, double v0, const CompactTensor& tensor,
                 cv::Point origin, double bound) {
  if (t.offsets.empty()) return 1e30;
  const double n = static_cast<double>(t.offsets.size());
  const double give_up = std::min(1e9, bound * n * CompactTensor::kScale);
  const int total = tensor.sum(t.offsets, t.bins, u0 - origin.x, v0 - origin.y, static_cast<int>(give_up));
  return total / (n * CompactTensor::kScale);
}

// Positions of the origin's pixel, along one axis, at which the template's extent
// [lo, hi] (offsets) covers the box's [start, end] within `slack`.
std::vector<double> positions(double lo, double hi, double start, double end, double slack,
                              const SearchParams& params) {
  const double first = end - slack - hi, last = start + slack - lo;
  std::vector<double> out;
  if (last < first) {
    out.push_back(0.5 * (first + last));  // the template is narrower: centre it
    return out;
  }
  const double step = std::max(params.position_step, (last - first) / std::max(1, params.grid_positions - 1));
  for (double p = first; p <= last + 1e-9; p += step) out.push_back(p);
  return out;
}

Eigen::Matrix3d in_plane_rotation(int step, int steps) {
  return Eigen::AngleAxisd(2.0 * M_PI * step / steps, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

}  // namespace

void SearchParams::check() const {
  auto require = [](bool ok, const char* field, const char* what) {
    if (!ok) throw InputError(std::string("search parameter ") + field, what);
  };
  require(coarse_points >= 4, "coarse_points", "must be at least 4");
  require(position_step > 0.0 && position_step <= 64.0, "position_step", "must be in (0, 64] pixels");
  require(grid_positions >= 1 && grid_positions <= 1000, "grid_positions", "must be in 1..1000");
  require(refined_templates >= 1, "refined_templates", "must be at least 1");
  require(min_cover > 0.0 && min_cover <= 1.0, "min_cover", "must be in (0, 1]");
  require(max_area_ratio >= 1.0, "max_area_ratio", "must be at least 1");
  require(candidates >= 1 && candidates <= 1000, "candidates", "must be in 1..1000");
}

Pose pose_on_ray(const Eigen::Matrix3d& on_axis_rotation, const Eigen::Vector2d& origin_pixel,
                 double depth, const PinholeCamera& camera) {
  const Eigen::Vector3d ray((origin_pixel.x() - camera.cx) / camera.fx,
                            (origin_pixel.y() - camera.cy) / camera.fy, 1.0);
  const Eigen::Matrix3d turn =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), ray.normalized()).toRotationMatrix();
  Pose pose;
  pose.R = turn * on_axis_rotation;
  pose.t = depth * ray;
  return pose;
}

namespace {

// A template's best fit so far: its mean cost with its origin at `origin` (pixels).
struct TemplateFit {
  double cost;
  Eigen::Vector2d origin;
  int view, in_plane;
  double depth;
  double step_x, step_y;  // spacing of the coarse grid it was found on
};

// By cost, then by view and rotation: a max-heap in this order holds the best fits.
bool better_fit(const TemplateFit& a, const TemplateFit& b) {
  if (a.cost != b.cost) return a.cost < b.cost;
  return std::make_pair(a.view, a.in_plane) < std::make_pair(b.view, b.in_plane);
}

// The search of one part's templates over one box: a coarse grid, then the best fits
// searched finely, then the distinct ones as candidates.
class BoxSearch {
 public:
  BoxSearch(const PartTemplates& part, int in_plane_steps, const DcdTensor& tensor,
            cv::Point tensor_origin, const PinholeCamera& camera, const cv::Rect& box,
            const SearchParams& params)
      : part_(part), in_plane_steps_(in_plane_steps), tensor_(tensor), compact_(tensor),
        tensor_origin_(tensor_origin), camera_(camera), box_(box), params_(params) {}

  // Every view and rotation on a coarse grid of positions (at most grid_positions per
  // axis over the range where it covers the box). Only the best refined_templates of
  // them go on, so a template may stop scoring once it cannot join them: the worst of
  // the best so far bounds every sum (the result is the same as scoring all in full).
  // The best fits come back as a max-heap (better_fit).
  std::vector<TemplateFit> coarse(double surface_depth) const {
    std::vector<TemplateFit> best;
    const std::size_t keep = static_cast<std::size_t>(params_.refined_templates);
    for (int v = 0; v < static_cast<int>(part_.views.size()); ++v) {
      const EdgeView& view = part_.views[v];
      const double depth = surface_depth - view.surface_depth_offset;
      if (depth <= 0.0) continue;
      const ProjectedView projected = project_view(view, depth, params_.coarse_points);
      if (projected.angles.empty()) continue;
      for (int k = 0; k < in_plane_steps_; ++k) {
        const double bound = best.size() < keep ? 1e30 : best.front().cost;
        TemplateFit here;
        if (!coarse_fit(projected, v, k, depth, bound, here)) continue;
        // `best` is a max-heap on (cost, view, rotation) holding the best `keep` so far.
        best.push_back(here);
        std::push_heap(best.begin(), best.end(), better_fit);
        if (best.size() > keep) {
          std::pop_heap(best.begin(), best.end(), better_fit);
          best.pop_back();
        }
      }
    }
    return best;
  }

  // ... then the best of them searched around their position at position_step, best first.
  void refine(std::vector<TemplateFit>& best) const {
    std::sort_heap(best.begin(), best.end(), better_fit);
    for (TemplateFit& b : best) {
      const ProjectedView projected = project_view(part_.views[b.view], b.depth, params_.coarse_points);
      const ProjectedTemplate t = turn_view(projected, 2.0 * M_PI * b.in_plane / in_plane_steps_, camera_, tensor_);
      const Eigen::Vector2d centre = b.origin;
      for (double du = -b.step_x / 2; du <= b.step_x / 2 + 1e-9; du += params_.position_step) {
        for (double dv = -b.step_y / 2; dv <= b.step_y / 2 + 1e-9; dv += params_.position_step) {
          const double cost = mean_cost(t, centre.x() + du, centre.y() + dv, compact_, tensor_origin_, b.cost);
          if (cost < b.cost) {
            b.cost = cost;
            b.origin = centre + Eigen::Vector2d(du, dv);
          }
        }
      }
    }
    std::sort(best.begin(), best.end(), better_fit);
  }

  // Neighbouring views and rotations of one good fit score alike: keep only candidates
  // that differ from those kept by a turn or a shift, so the refinement starts from
  // distinct hypotheses.
  std::vector<PoseCandidate> distinct_candidates(const std::vector<TemplateFit>& best) const {
    std::vector<PoseCandidate> candidates;
    for (const TemplateFit& b : best) {
      if (static_cast<int>(candidates.size()) >= params_.candidates) break;
      const Eigen::Matrix3d rotation = in_plane_rotation(b.in_plane, in_plane_steps_) * part_.views[b.view].rotation;
      PoseCandidate c;
      c.pose = pose_on_ray(rotation, b.origin, b.depth, camera_);
      c.cost = b.cost;
      c.view = b.view;
      c.in_plane = b.in_plane;
      bool distinct = true;
      for (const PoseCandidate& kept : candidates) {
        const double turn = std::acos(std::clamp(((kept.pose.R.transpose() * c.pose.R).trace() - 1.0) / 2.0, -1.0, 1.0));
        const double shift = (camera_.project(kept.pose.t) - camera_.project(c.pose.t)).norm();
        if (turn < params_.distinct_degrees * M_PI / 180.0 && shift < params_.distinct_pixels) distinct = false;
      }
      if (distinct) candidates.push_back(c);
    }
    return candidates;
  }

 private:
  // The best fit of view `v` turned by in-plane step `k` on the coarse grid, if it costs
  // less than `bound`; false when it does not, or when the template cannot match the box.
  bool coarse_fit(const ProjectedView& projected, int v, int k, double depth, double bound,
                  TemplateFit& here) const {
    const ProjectedTemplate t = turn_view(projected, 2.0 * M_PI * k / in_plane_steps_, camera_, tensor_);
    const Eigen::Vector2d size = t.bounds.sizes();
    if (size.x() < params_.min_cover * box_.width || size.y() < params_.min_cover * box_.height) return false;
    if (size.x() * size.y() > params_.max_area_ratio * box_.area()) return false;
    const double slack_x = std::max(3.0, 0.1 * box_.width), slack_y = std::max(3.0, 0.1 * box_.height);
    const std::vector<double> us = positions(t.bounds.min().x(), t.bounds.max().x(), box_.x, box_.x + box_.width - 1, slack_x, params_);
    const std::vector<double> vs = positions(t.bounds.min().y(), t.bounds.max().y(), box_.y, box_.y + box_.height - 1, slack_y, params_);
    // The origin is set with the first fit under `bound` (none: `here` is not used).
    here = {bound, Eigen::Vector2d::Zero(), v, k, depth, us.size() > 1 ? us[1] - us[0] : 0.0, vs.size() > 1 ? vs[1] - vs[0] : 0.0};
    bool found = false;
    for (double u0 : us) {
      for (double v0 : vs) {
        const double cost = mean_cost(t, u0, v0, compact_, tensor_origin_, here.cost);
        if (cost < here.cost) {
          here = {cost, {u0, v0}, v, k, depth, here.step_x, here.step_y};
          found = true;
        }
      }
    }
    return found;
  }

  const PartTemplates& part_;
  const int in_plane_steps_;
  const DcdTensor& tensor_;
  const CompactTensor compact_;
  const cv::Point tensor_origin_;
  const PinholeCamera& camera_;
  const cv::Rect& box_;
  const SearchParams& params_;
};

}  // namespace

std::vector<PoseCandidate> search_templates(const PartTemplates& part, int in_plane_steps,
                                            const DcdTensor& tensor, cv::Point tensor_origin,
                                            const PinholeCamera& camera, const cv::Rect& box,
                                            double surface_depth, const SearchParams& params) {
  params.check();
  if (box.width <= 0 || box.height <= 0) throw InputError("box", "is empty");
  const BoxSearch search(part, in_plane_steps, tensor, tensor_origin, camera, box, params);
  std::vector<TemplateFit> best = search.coarse(surface_depth);
  search.refine(best);
  return search.distinct_candidates(best);
}

}  // namespace flexsight

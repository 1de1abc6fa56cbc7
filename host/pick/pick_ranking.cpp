#include "host/pick/pick_ranking.h"

#include <algorithm>
#include <cmath>

namespace flexsight {

double visible_fraction(const std::shared_ptr<const Mesh>& mesh, const Pose& pose, const PinholeCamera& camera, const cv::Mat& depth_mm,
                        double tolerance_mm) {
  RenderScene scene;
  scene.add_instance(scene.add_mesh(mesh), pose);
  scene.commit();
  RaycastOptions options;
  options.threads = 1;
  options.areas = {projected_area(*mesh, pose, camera)};
  const RaycastImages images = raycast(scene, camera, options);
  long part = 0, seen = 0;
  for (int y = 0; y < images.depth.rows; ++y) {
    for (int x = 0; x < images.depth.cols; ++x) {
      const float model_z = images.depth.at<float>(y, x);
      if (!(model_z > 0.0f)) continue;
      ++part;
      const float measured = depth_mm.at<float>(y, x);
      const bool hidden = measured > 0.0f && measured < model_z - tolerance_mm;  // NaN compares false
      if (!hidden) ++seen;
    }
  }
  return part == 0 ? 0.0 : static_cast<double>(seen) / part;
}

double floor_depth_mm(const cv::Mat& depth_mm) {
  std::vector<float> values;
  values.reserve(depth_mm.total());
  for (auto it = depth_mm.begin<float>(); it != depth_mm.end<float>(); ++it) {
    if (*it > 0.0f && std::isfinite(*it)) values.push_back(*it);
  }
  if (values.empty()) return 0.0;
  const std::size_t k = std::min(values.size() - 1, static_cast<std::size_t>(0.95 * values.size()));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

void rank_picks(std::vector<PickCandidate>& candidates) {
  for (PickCandidate& c : candidates) c.pick_score = c.pose_score * c.visible_fraction;
  std::stable_sort(candidates.begin(), candidates.end(), [](const PickCandidate& a, const PickCandidate& b) {
    if (a.pick_score != b.pick_score) return a.pick_score > b.pick_score;
    return a.height_mm > b.height_mm;
  });
}

namespace {

double box_iou(const ObjectDetection& a, const ObjectDetection& b) {
  const double w = std::min(a.box[2], b.box[2]) - std::max(a.box[0], b.box[0]);
  const double h = std::min(a.box[3], b.box[3]) - std::max(a.box[1], b.box[1]);
  if (w <= 0.0 || h <= 0.0) return 0.0;
  const double area_a = (a.box[2] - a.box[0]) * (a.box[3] - a.box[1]);
  const double area_b = (b.box[2] - b.box[0]) * (b.box[3] - b.box[1]);
  return w * h / (area_a + area_b - w * h);
}

}  // namespace

std::vector<int> pose_proposals(const std::vector<ObjectDetection>& detections, int classes_per_box, double iou) {
  std::vector<int> order(detections.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return detections[a].score > detections[b].score; });
  struct Group {
    int lead;
    std::vector<int> members;
  };
  std::vector<Group> groups;
  std::vector<int> chosen;
  for (int i : order) {
    const ObjectDetection& d = detections[i];
    auto group = std::find_if(groups.begin(), groups.end(),
                              [&](const Group& g) { return box_iou(detections[g.lead], d) > iou; });
    if (group == groups.end()) {
      groups.push_back({i, {i}});
      chosen.push_back(i);
      continue;
    }
    const bool known = std::any_of(group->members.begin(), group->members.end(),
                                   [&](int m) { return detections[m].category_id == d.category_id; });
    if (known || static_cast<int>(group->members.size()) >= classes_per_box) continue;
    group->members.push_back(i);
    chosen.push_back(i);
  }
  return chosen;
}

void remove_duplicate_picks(std::vector<PickCandidate>& ranked, double iou) {
  std::vector<PickCandidate> kept;
  for (const PickCandidate& c : ranked) {
    const bool duplicate = std::any_of(kept.begin(), kept.end(), [&](const PickCandidate& k) {
      const double inter = (c.box & k.box).area();
      return inter > iou * (c.box.area() + k.box.area() - inter);
    });
    if (!duplicate) kept.push_back(c);
  }
  ranked = std::move(kept);
}

}  // namespace flexsight

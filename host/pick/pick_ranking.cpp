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

}  // namespace flexsight

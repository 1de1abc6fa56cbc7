#include "host/pick/candidate_order.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace flexsight {
namespace {

// A measured surface counts as nearer than the part only beyond this: stereo depth is a
// few millimetres off at a metre.
constexpr double kNearerToleranceMm = 10.0;
// The part's top: this percentile of the depths in the box centre (nearest first); low
// enough to find the top, high enough to ignore a few wrong near depths.
constexpr double kTopPercentile = 0.1;

bool measured(float depth) { return depth > 0.0f && std::isfinite(depth); }

// The valid depths of `depth_mm` in `rect` (clipped to the image).
std::vector<float> depths_in(const cv::Mat& depth_mm, cv::Rect rect) {
  rect &= cv::Rect(0, 0, depth_mm.cols, depth_mm.rows);
  std::vector<float> values;
  values.reserve(static_cast<std::size_t>(std::max(0, rect.area())));
  for (int y = rect.y; y < rect.y + rect.height; ++y) {
    const float* row = depth_mm.ptr<float>(y);
    for (int x = rect.x; x < rect.x + rect.width; ++x) {
      if (measured(row[x])) values.push_back(row[x]);
    }
  }
  return values;
}

float percentile(std::vector<float> values, double p) {
  const std::size_t k = std::min(values.size() - 1, static_cast<std::size_t>(p * values.size()));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

double iou(const cv::Rect& a, const cv::Rect& b) {
  const double inter = (a & b).area();
  const double uni = a.area() + b.area() - inter;
  return uni > 0.0 ? inter / uni : 0.0;
}

}  // namespace

std::vector<std::vector<int>> group_overlapping_boxes(const std::vector<cv::Rect>& boxes, double iou_threshold) {
  std::vector<std::vector<int>> groups;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
    auto group = std::find_if(groups.begin(), groups.end(),
                              [&](const std::vector<int>& g) { return iou(boxes[g.front()], boxes[i]) > iou_threshold; });
    if (group == groups.end()) {
      groups.push_back({i});
    } else {
      group->push_back(i);
    }
  }
  return groups;
}

CandidateCues depth_cues(const cv::Mat& depth_mm, const cv::Rect& box, double floor_depth_mm) {
  CandidateCues cues;
  const cv::Rect centre(box.x + box.width / 4, box.y + box.height / 4, std::max(1, box.width / 2),
                        std::max(1, box.height / 2));
  const std::vector<float> centre_depths = depths_in(depth_mm, centre);
  if (centre_depths.empty()) return cues;
  const double top = percentile(centre_depths, kTopPercentile);
  const double middle = percentile(centre_depths, 0.5);
  if (floor_depth_mm > 0.0) cues.height_mm = std::max(0.0, floor_depth_mm - top);

  const cv::Rect image(0, 0, depth_mm.cols, depth_mm.rows);
  const cv::Rect inner = box & image;
  const int margin_x = std::max(1, box.width / 4), margin_y = std::max(1, box.height / 4);
  const cv::Rect outer = cv::Rect(box.x - margin_x, box.y - margin_y, box.width + 2 * margin_x, box.height + 2 * margin_y) & image;
  long ring = 0, ring_free = 0, inside = 0, inside_seen = 0;
  for (int y = outer.y; y < outer.y + outer.height; ++y) {
    const float* row = depth_mm.ptr<float>(y);
    for (int x = outer.x; x < outer.x + outer.width; ++x) {
      if (!measured(row[x])) continue;
      if (inner.contains(cv::Point(x, y))) {
        ++inside;
        if (row[x] >= middle - kNearerToleranceMm) ++inside_seen;
      } else {
        ++ring;
        if (row[x] >= top - kNearerToleranceMm) ++ring_free;
      }
    }
  }
  cues.free_space = ring > 0 ? static_cast<double>(ring_free) / ring : 1.0;
  cues.visible_estimate = inside > 0 ? static_cast<double>(inside_seen) / inside : 0.0;
  return cues;
}

void order_candidates(std::vector<OrderedCandidate>& candidates, const CandidateOrderWeights& weights) {
  double highest = 0.0;
  for (const OrderedCandidate& c : candidates) highest = std::max(highest, c.cues.height_mm);
  for (OrderedCandidate& c : candidates) {
    const CandidateCues& q = c.cues;
    c.cheap_score = weights.height * (highest > 0.0 ? q.height_mm / highest : 0.0) +
                    weights.free_space * q.free_space + weights.visible * q.visible_estimate +
                    weights.detection * q.detection_score +
                    (q.naming_score >= 0.0 ? weights.naming * q.naming_score : 0.0);
  }
  std::stable_sort(candidates.begin(), candidates.end(), [](const OrderedCandidate& a, const OrderedCandidate& b) {
    if (a.cheap_score != b.cheap_score) return a.cheap_score > b.cheap_score;
    return a.proposals.front() < b.proposals.front();
  });
}

}  // namespace flexsight

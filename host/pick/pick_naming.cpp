#include "host/pick/pick_naming.h"

#include <algorithm>
#include <numeric>

#include "host/io/input_error.h"

namespace flexsight {
namespace {

// A class the detector did not propose in a group still gets this much of its score, so
// the namer can bring a class the detector missed.
constexpr double kUnproposedDetectorScore = 0.05;

double box_iou(const float a[4], const float b[4]) {
  const double w = std::min(a[2], b[2]) - std::max(a[0], b[0]);
  const double h = std::min(a[3], b[3]) - std::max(a[1], b[1]);
  if (w <= 0.0 || h <= 0.0) return 0.0;
  const double area_a = (a[2] - a[0]) * (a[3] - a[1]);
  const double area_b = (b[2] - b[0]) * (b[3] - b[1]);
  return w * h / (area_a + area_b - w * h);
}

}  // namespace

NamingMix parse_naming_mix(const std::string& text, const std::string& option) {
  if (text == "namer") return NamingMix::Namer;
  if (text == "product") return NamingMix::Product;
  throw InputError(option, "must be namer or product, got '" + text + "'");
}

std::vector<NamedProposal> named_proposals(const std::vector<ObjectDetection>& detections, PartNamer& namer,
                                           const cv::Mat& bgr, int classes_per_box, double iou, NamingMix mix) {
  std::vector<int> order(detections.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return detections[a].score > detections[b].score; });
  const int classes = static_cast<int>(namer.labels().size());
  struct Group {
    int lead;
    std::vector<double> detector_score;  // per namer class, the best in the group
  };
  std::vector<Group> groups;
  for (int i : order) {
    const ObjectDetection& d = detections[i];
    auto group = std::find_if(groups.begin(), groups.end(),
                              [&](const Group& g) { return box_iou(detections[g.lead].box, d.box) > iou; });
    if (group == groups.end()) {
      groups.push_back({i, std::vector<double>(classes, 0.0)});
      group = groups.end() - 1;
    }
    const int c = namer.class_of(d.category_id);
    if (c >= 0) group->detector_score[c] = std::max<double>(group->detector_score[c], d.score);
  }
  std::vector<NamedProposal> proposals;
  for (const Group& g : groups) {
    const ObjectDetection& lead = detections[g.lead];
    const std::vector<float> p = namer.name(bgr, lead.box);
    std::vector<double> key(classes);
    for (int c = 0; c < classes; ++c) {
      key[c] = mix == NamingMix::Namer ? p[c] : p[c] * (g.detector_score[c] + kUnproposedDetectorScore);
    }
    std::vector<int> best(classes);
    std::iota(best.begin(), best.end(), 0);
    std::stable_sort(best.begin(), best.end(), [&](int a, int b) { return key[a] > key[b]; });
    for (int k = 0; k < std::min(classes_per_box, classes); ++k) {
      NamedProposal named;
      named.detection = lead;
      named.detection.category_id = namer.labels()[best[k]].category_id;
      named.detection.score = static_cast<float>(g.detector_score[best[k]]);
      named.naming_score = p[best[k]];
      proposals.push_back(named);
    }
  }
  return proposals;
}

}  // namespace flexsight

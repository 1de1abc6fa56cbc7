#include "host/eval/coco_box_eval.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>

namespace flexsight::coco_eval {
namespace {

constexpr int kRecallPoints = 101;
// Area range "all": [0 ** 2, 1e5 ** 2].
constexpr double kMinArea = 0.0;
constexpr double kMaxArea = 1e10;

// np.linspace(0, 1, 101): i * (1 / 100), the last one exactly 1.
double recall_threshold(int i) { return i == kRecallPoints - 1 ? 1.0 : i * (1.0 / 100.0); }

// What evaluateImg returns for one image and class: the kept detections' scores (best
// first), and per IoU threshold whether each is matched and whether it is ignored.
struct ImageEval {
  std::vector<double> scores;
  std::array<std::vector<std::uint8_t>, kThresholds> matched;
  std::array<std::vector<std::uint8_t>, kThresholds> ignored;
  int regular_truth = 0;  // ground truth not ignored: what recall counts
};

bool outside_area_range(double area) { return area < kMinArea || area > kMaxArea; }

std::optional<ImageEval> evaluate_image(const std::vector<const TruthBox*>& truth_in,
                                        const std::vector<const DetectedBox*>& detections_in,
                                        int max_detections) {
  if (truth_in.empty() && detections_in.empty()) return std::nullopt;
  // Ground truth: crowd regions (and boxes outside the area range) are "ignored" and
  // sorted last, stably (np.argsort(kind="mergesort")).
  std::vector<const TruthBox*> truth = truth_in;
  const auto ignored_truth = [](const TruthBox* box) {
    return box->crowd || outside_area_range(box->area);
  };
  std::stable_sort(truth.begin(), truth.end(), [&](const TruthBox* a, const TruthBox* b) {
    return !ignored_truth(a) && ignored_truth(b);
  });
  // Detections: highest score first, stably, the first max_detections kept.
  std::vector<const DetectedBox*> detections = detections_in;
  std::stable_sort(detections.begin(), detections.end(),
                   [](const DetectedBox* a, const DetectedBox* b) { return -a->score < -b->score; });
  if (static_cast<int>(detections.size()) > max_detections) detections.resize(max_detections);

  const std::size_t G = truth.size(), D = detections.size();
  std::vector<std::uint8_t> truth_ignored(G);
  ImageEval result;
  for (std::size_t g = 0; g < G; ++g) {
    truth_ignored[g] = ignored_truth(truth[g]) ? 1 : 0;
    if (!truth_ignored[g]) ++result.regular_truth;
  }
  std::vector<double> ious(D * G);
  for (std::size_t d = 0; d < D; ++d) {
    result.scores.push_back(detections[d]->score);
    for (std::size_t g = 0; g < G; ++g) {
      ious[d * G + g] = box_iou(detections[d]->bbox, truth[g]->bbox, truth[g]->crowd);
    }
  }
  const std::array<double, kThresholds> thresholds = iou_thresholds();
  for (int t = 0; t < kThresholds; ++t) {
    std::vector<std::uint8_t>& dt_matched = result.matched[t];
    std::vector<std::uint8_t>& dt_ignored = result.ignored[t];
    dt_matched.assign(D, 0);
    dt_ignored.assign(D, 0);
    std::vector<std::uint8_t> gt_matched(G, 0);
    for (std::size_t d = 0; d < D; ++d) {
      // The best ground truth not yet taken (crowd regions can take many); a regular
      // match is never traded for an ignored one. Ties go to the later box, as the
      // "<" test below lets an equal IoU replace the match.
      double best = std::min(thresholds[t], 1 - 1e-10);
      int m = -1;
      for (std::size_t g = 0; g < G; ++g) {
        if (gt_matched[g] && !truth[g]->crowd) continue;
        if (m > -1 && !truth_ignored[m] && truth_ignored[g]) break;
        if (ious[d * G + g] < best) continue;
        best = ious[d * G + g];
        m = static_cast<int>(g);
      }
      if (m == -1) continue;
      dt_ignored[d] = truth_ignored[m];
      dt_matched[d] = 1;
      gt_matched[m] = 1;
    }
    // Unmatched detections outside the area range are ignored too (loadRes: area = w h).
    for (std::size_t d = 0; d < D; ++d) {
      const double area = detections[d]->bbox[2] * detections[d]->bbox[3];
      if (!dt_matched[d] && outside_area_range(area)) dt_ignored[d] = 1;
    }
  }
  return result;
}

}  // namespace

std::array<double, kThresholds> iou_thresholds() {
  // np.linspace(.5, .95, 10): start + i * ((stop - start) / 9), the last one exactly stop.
  std::array<double, kThresholds> thresholds{};
  const double step = (0.95 - 0.5) / (kThresholds - 1);
  for (int i = 0; i < kThresholds; ++i) thresholds[i] = i * step + 0.5;
  thresholds[kThresholds - 1] = 0.95;
  return thresholds;
}

ClassAp evaluate_class(const std::vector<std::vector<const TruthBox*>>& truth,
                       const std::vector<std::vector<const DetectedBox*>>& detections,
                       int max_detections) {
  // evaluateImg for every image, then accumulate's concatenation in image order.
  struct Ranked {
    double score;
    const ImageEval* image;
    std::size_t index;
  };
  std::vector<ImageEval> images;
  images.reserve(truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (auto image = evaluate_image(truth[i], detections[i], max_detections)) {
      images.push_back(std::move(*image));
    }
  }
  ClassAp result;
  int regular_truth = 0;
  std::vector<Ranked> ranked;
  for (const ImageEval& image : images) {
    regular_truth += image.regular_truth;
    for (std::size_t d = 0; d < image.scores.size(); ++d) ranked.push_back({image.scores[d], &image, d});
  }
  if (regular_truth == 0) return result;
  result.defined = true;
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const Ranked& a, const Ranked& b) { return -a.score < -b.score; });

  const std::size_t nd = ranked.size();
  const double spacing = std::numeric_limits<double>::epsilon();  // np.spacing(1)
  std::vector<double> recall(nd), precision(nd);
  for (int t = 0; t < kThresholds; ++t) {
    double tp = 0, fp = 0;
    for (std::size_t k = 0; k < nd; ++k) {
      const ImageEval& image = *ranked[k].image;
      const std::size_t d = ranked[k].index;
      if (!image.ignored[t][d]) (image.matched[t][d] ? tp : fp) += 1;
      recall[k] = tp / regular_truth;
      precision[k] = tp / (fp + tp + spacing);
    }
    for (std::size_t k = nd; k-- > 1;) {
      if (precision[k] > precision[k - 1]) precision[k - 1] = precision[k];
    }
    // Precision at each recall threshold: at the first point whose recall reaches it
    // (np.searchsorted, side "left"); 0 from the first threshold no point reaches.
    double sum = 0;
    for (int r = 0; r < kRecallPoints; ++r) {
      const auto at = std::lower_bound(recall.begin(), recall.end(), recall_threshold(r));
      if (at == recall.end()) break;
      sum += precision[static_cast<std::size_t>(at - recall.begin())];
    }
    result.ap[t] = sum / kRecallPoints;
  }
  return result;
}

}  // namespace flexsight::coco_eval

#include "host/eval/voc_matching.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>

namespace flexsight {

double box_size_px(const BoxXywh& box) { return std::sqrt(std::max(0.0, box[2] * box[3])); }

bool SizeRange::contains(const BoxXywh& box) const {
  const double size = box_size_px(box);
  return size >= min_px && size < max_px;
}

int VocMatching::matched_from(double min_score) const {
  return static_cast<int>(std::count_if(match_scores.begin(), match_scores.end(),
                                        [&](double score) { return score >= min_score; }));
}

namespace {

struct Record {
  double score;
  std::size_t image;
  const DetectedBox* box;
};

// The unmatched non-crowd box of `truth` with the highest IoU with `box` (the first on
// ties), or -1 when there is none; its IoU in `best_iou`.
int best_unmatched(const std::vector<const TruthBox*>& truth, const std::vector<std::uint8_t>& used,
                   const DetectedBox& box, double& best_iou) {
  int best = -1;
  best_iou = -1;
  for (std::size_t g = 0; g < truth.size(); ++g) {
    if (truth[g]->crowd || used[g]) continue;
    const double iou = box_iou(box.bbox, truth[g]->bbox);
    if (iou > best_iou) {
      best_iou = iou;
      best = static_cast<int>(g);
    }
  }
  return best;
}

bool covers_crowd(const std::vector<const TruthBox*>& truth, const DetectedBox& box, double threshold) {
  return std::any_of(truth.begin(), truth.end(), [&](const TruthBox* t) {
    return t->crowd && box_iou(box.bbox, t->bbox, true) >= threshold;
  });
}

// The envelope (precision monotone from the right), then the area under it: recall
// steps from 0 to the last point's recall (beyond it the envelope is 0).
double envelope_area(PrCurve& curve) {
  std::vector<double>& precision = curve.precision;
  for (std::size_t k = precision.size(); k-- > 1;) precision[k - 1] = std::max(precision[k - 1], precision[k]);
  double area = 0, previous_recall = 0;
  for (std::size_t k = 0; k < precision.size(); ++k) {
    area += (curve.recall[k] - previous_recall) * precision[k];
    previous_recall = curve.recall[k];
  }
  return area;
}

}  // namespace

VocMatching voc_match(const ClassBoxes& boxes, double threshold, const SizeRange& range) {
  std::vector<Record> records;
  std::vector<std::vector<std::uint8_t>> used(boxes.truth.size());
  VocMatching result;
  for (std::size_t i = 0; i < boxes.truth.size(); ++i) {
    used[i].assign(boxes.truth[i].size(), 0);
    for (const TruthBox* truth : boxes.truth[i]) {
      result.positives += !truth->crowd && range.contains(truth->bbox) ? 1 : 0;
    }
    for (const DetectedBox* box : boxes.detections[i]) records.push_back({box->score, i, box});
  }
  std::stable_sort(records.begin(), records.end(),
                   [](const Record& a, const Record& b) { return a.score > b.score; });
  if (result.positives == 0) {
    result.ap = std::nan("");
    return result;
  }
  double tp = 0, fp = 0;
  for (const Record& record : records) {
    const std::vector<const TruthBox*>& truth = boxes.truth[record.image];
    double best_iou = -1;
    const int best = best_unmatched(truth, used[record.image], *record.box, best_iou);
    if (best >= 0 && best_iou >= threshold) {
      used[record.image][best] = 1;
      if (!range.contains(truth[best]->bbox)) continue;
      tp += 1;
      result.match_scores.push_back(record.score);
    } else if (covers_crowd(truth, *record.box, threshold) || !range.contains(record.box->bbox)) {
      continue;
    } else {
      fp += 1;
    }
    result.curve.recall.push_back(tp / result.positives);
    result.curve.precision.push_back(tp / (tp + fp));
  }
  result.ap = envelope_area(result.curve);
  return result;
}

std::vector<ClassBoxes> boxes_by_class(const std::vector<std::vector<TruthBox>>& truth,
                                       const std::vector<std::vector<DetectedBox>>& detections,
                                       const std::vector<DetectionCategory>& categories) {
  std::map<int, std::size_t> class_of_id;
  std::vector<ClassBoxes> boxes(categories.size());
  for (std::size_t c = 0; c < categories.size(); ++c) {
    if (!class_of_id.emplace(categories[c].id, c).second) {
      throw std::invalid_argument("boxes_by_class: category " +
                                  std::to_string(categories[c].id) + " is listed twice");
    }
    boxes[c].truth.resize(truth.size());
    boxes[c].detections.resize(truth.size());
  }
  const auto class_index = [&](int category_id) {
    const auto found = class_of_id.find(category_id);
    if (found == class_of_id.end()) {
      throw std::invalid_argument("boxes_by_class: a box of category " +
                                  std::to_string(category_id) + ", which is not listed");
    }
    return found->second;
  };
  for (std::size_t i = 0; i < truth.size(); ++i) {
    for (const TruthBox& box : truth[i]) {
      const std::size_t c = class_index(box.category_id);
      boxes[c].truth[i].push_back(&box);
    }
    for (const DetectedBox& box : detections[i]) {
      const std::size_t c = class_index(box.category_id);
      boxes[c].detections[i].push_back(&box);
    }
  }
  return boxes;
}

}  // namespace flexsight

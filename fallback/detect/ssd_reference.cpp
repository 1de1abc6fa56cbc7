#include "fallback/detect/ssd_reference.h"

#include <algorithm>
#include <numeric>

namespace flexsight {

void decode_boxes(const std::vector<float>& encodings, const std::vector<float>& anchors,
                  int anchor_count, const SsdBoxScale& scale, std::vector<float>& boxes) {
  boxes.assign(4 * static_cast<size_t>(anchor_count), 0.0f);
  for (int a = 0; a < anchor_count; ++a) {
    const SsdBox box = ssd_decode_box(&encodings[4 * a], &anchors[4 * a], scale.y, scale.x,
                                      scale.h, scale.w);
    boxes[4 * a + 0] = box.x_min;
    boxes[4 * a + 1] = box.y_min;
    boxes[4 * a + 2] = box.x_max;
    boxes[4 * a + 3] = box.y_max;
  }
}

void class_scores(const std::vector<float>& logits, int anchor_count, int classes,
                  int score_function, std::vector<float>& scores) {
  scores.assign(static_cast<size_t>(classes) * anchor_count, 0.0f);
  for (int a = 0; a < anchor_count; ++a) {
    const float* row = &logits[static_cast<size_t>(a) * (classes + 1)];
    if (score_function == SSD_SCORE_SOFTMAX) {
      ssd_softmax_scores(row, classes, &scores[a], anchor_count);
      continue;
    }
    for (int c = 0; c < classes; ++c) {
      scores[static_cast<size_t>(c) * anchor_count + a] = ssd_sigmoid_score(row[c + 1]);
    }
  }
}

void gather_candidates(const std::vector<float>& scores, int anchor_count, int classes,
                       float score_threshold, std::vector<int>& candidates,
                       std::vector<float>& candidate_scores, std::vector<int>& counts) {
  const size_t size = static_cast<size_t>(classes) * anchor_count;
  candidates.assign(size, 0);
  candidate_scores.assign(size, 0.0f);
  counts.assign(classes, 0);
  for (int c = 0; c < classes; ++c) {
    const size_t base = static_cast<size_t>(c) * anchor_count;
    for (int a = 0; a < anchor_count; ++a) {
      const float score = scores[base + a];
      if (!(score > score_threshold)) continue;
      candidates[base + counts[c]] = a;
      candidate_scores[base + counts[c]] = score;
      ++counts[c];
    }
  }
}

void rank_candidates(const std::vector<int>& candidates,
                     const std::vector<float>& candidate_scores, const std::vector<int>& counts,
                     int anchor_count, int classes, int top_k, std::vector<int>& sorted) {
  sorted.assign(static_cast<size_t>(classes) * top_k, 0);
  std::vector<int> order;
  for (int c = 0; c < classes; ++c) {
    const size_t base = static_cast<size_t>(c) * anchor_count;
    order.resize(counts[c]);
    std::iota(order.begin(), order.end(), 0);
    const int kept = std::min(counts[c], top_k);
    std::partial_sort(order.begin(), order.begin() + kept, order.end(), [&](int i, int j) {
      return ssd_candidate_before(candidate_scores[base + i], candidates[base + i],
                                  candidate_scores[base + j], candidates[base + j]) != 0;
    });
    for (int rank = 0; rank < kept; ++rank) {
      sorted[static_cast<size_t>(c) * top_k + rank] = candidates[base + order[rank]];
    }
  }
}

void iou_mask(const std::vector<float>& boxes, const std::vector<int>& sorted,
              const std::vector<int>& counts, int classes, int top_k, float iou_threshold,
              std::vector<std::uint32_t>& mask) {
  const int words = SSD_MASK_WORDS(top_k);
  mask.assign(static_cast<size_t>(classes) * top_k * words, 0u);
  for (int c = 0; c < classes; ++c) {
    const int count = std::min(counts[c], top_k);
    const int* class_sorted = &sorted[static_cast<size_t>(c) * top_k];
    for (int i = 0; i < count; ++i) {
      for (int w = 0; w < words; ++w) {
        mask[(static_cast<size_t>(c) * top_k + i) * words + w] =
            ssd_mask_word(boxes.data(), class_sorted, count, i, w, iou_threshold);
      }
    }
  }
}

void nms_scan(const std::vector<std::uint32_t>& mask, const std::vector<int>& sorted,
              const std::vector<int>& counts, int classes, int top_k, std::vector<int>& kept,
              std::vector<int>& kept_counts) {
  const int words = SSD_MASK_WORDS(top_k);
  kept.assign(static_cast<size_t>(classes) * top_k, 0);
  kept_counts.assign(classes, 0);
  for (int c = 0; c < classes; ++c) {
    const size_t base = static_cast<size_t>(c) * top_k;
    kept_counts[c] = ssd_nms_scan_class(&mask[base * words], &sorted[base],
                                        std::min(counts[c], top_k), words, &kept[base]);
  }
}

void rank_detections(const std::vector<float>& scores, const std::vector<float>& boxes,
                     const std::vector<int>& kept, const std::vector<int>& kept_counts,
                     int anchor_count, int classes, int top_k, int max_detections,
                     std::vector<SsdDetectionRecord>& records, std::vector<int>& record_count) {
  std::vector<SsdDetectionRecord> survivors;
  for (int c = 0; c < classes; ++c) {
    for (int j = 0; j < kept_counts[c]; ++j) {
      SsdDetectionRecord record{};
      record.class_id = c;
      record.anchor = kept[static_cast<size_t>(c) * top_k + j];
      record.score = scores[static_cast<size_t>(c) * anchor_count + record.anchor];
      for (int k = 0; k < 4; ++k) record.box[k] = boxes[4 * record.anchor + k];
      survivors.push_back(record);
    }
  }
  const size_t count = std::min(survivors.size(), static_cast<size_t>(max_detections));
  std::partial_sort(survivors.begin(), survivors.begin() + count, survivors.end(),
                    [](const SsdDetectionRecord& a, const SsdDetectionRecord& b) {
                      return ssd_detection_before(a.score, a.class_id, a.anchor, b.score,
                                                  b.class_id, b.anchor) != 0;
                    });
  records.assign(max_detections, SsdDetectionRecord{});
  std::copy(survivors.begin(), survivors.begin() + count, records.begin());
  record_count.assign(1, static_cast<int>(count));
}

}  // namespace flexsight

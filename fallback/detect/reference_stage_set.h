#pragma once
// The reference path as a stage set of SSD post-processing's one schedule
// (host/detect/ssd_schedule.h): the functions of ssd_reference.h with the signatures of
// the OpenCL stages (host/detect/opencl_ssd_stages.h), over std::vector. Nothing here
// computes; it adapts.
#include <cstdint>
#include <vector>

#include "fallback/detect/ssd_reference.h"

namespace flexsight {

class ReferenceSsdStages {
 public:
  template <class T>
  using Array = std::vector<T>;

  template <class T>
  Array<T> array(size_t count, const char* /*what*/) {
    return Array<T>(count);
  }
  Array<float> upload(const float* values, size_t count, const char* /*what*/) {
    return Array<float>(values, values + count);
  }
  // The first record_count[0] records.
  std::vector<SsdDetectionRecord> download_records(const Array<SsdDetectionRecord>& records,
                                                   const Array<int>& record_count) {
    return {records.begin(), records.begin() + record_count[0]};
  }

  void decode_boxes(const Array<float>& encodings, const Array<float>& anchors,
                    int anchor_count, const SsdBoxScale& scale, Array<float>& boxes) {
    flexsight::decode_boxes(encodings, anchors, anchor_count, scale, boxes);
  }
  void class_scores(const Array<float>& logits, int anchor_count, int classes,
                    int score_function, Array<float>& scores) {
    flexsight::class_scores(logits, anchor_count, classes, score_function, scores);
  }
  void gather_candidates(const Array<float>& scores, int anchor_count, int classes,
                         float score_threshold, Array<int>& candidates,
                         Array<float>& candidate_scores, Array<int>& counts) {
    flexsight::gather_candidates(scores, anchor_count, classes, score_threshold, candidates,
                                 candidate_scores, counts);
  }
  void rank_candidates(const Array<int>& candidates, const Array<float>& candidate_scores,
                       const Array<int>& counts, int anchor_count, int classes, int top_k,
                       Array<int>& sorted) {
    flexsight::rank_candidates(candidates, candidate_scores, counts, anchor_count, classes,
                               top_k, sorted);
  }
  void iou_mask(const Array<float>& boxes, const Array<int>& sorted, const Array<int>& counts,
                int classes, int top_k, float iou_threshold, Array<std::uint32_t>& mask) {
    flexsight::iou_mask(boxes, sorted, counts, classes, top_k, iou_threshold, mask);
  }
  void nms_scan(const Array<std::uint32_t>& mask, const Array<int>& sorted,
                const Array<int>& counts, int classes, int top_k, Array<int>& kept,
                Array<int>& kept_counts) {
    flexsight::nms_scan(mask, sorted, counts, classes, top_k, kept, kept_counts);
  }
  void rank_detections(const Array<float>& scores, const Array<float>& boxes,
                       const Array<int>& kept, const Array<int>& kept_counts, int anchor_count,
                       int classes, int top_k, int max_detections,
                       Array<SsdDetectionRecord>& records, Array<int>& record_count) {
    flexsight::rank_detections(scores, boxes, kept, kept_counts, anchor_count, classes, top_k,
                               max_detections, records, record_count);
  }
};

}  // namespace flexsight

#pragma once
// The one schedule of SSD post-processing, as the algorithm reads, over a stage set that
// both paths implement with the same signatures:
//   - ReferenceSsdStages (fallback/detect/reference_stage_set.h): scalar C++ on vectors;
//   - OpenClSsdStages (host/detect/opencl_ssd_stages.h): the kernels on device buffers.
// Both give the same bytes because each stage does (tests/detect/opencl/).
//
// A stage set S provides, besides the stages:
//   template <class T> using Array;            std::vector<T> or Buffer<T>
//   array<T>(count, what)                      an output ("what" names it in errors)
//   download_records(records, record_count)    the first record_count[0] records
#include <algorithm>
#include <cstdint>
#include <vector>

#include "host/detect/ssd_params.h"

namespace flexsight {

// The schedule with its intermediate arrays, kept across runs of one shape (the
// detector runs frame after frame with the same anchors, classes and limits).
template <class Stages>
class SsdSchedule {
 public:
  template <class T>
  using Array = typename Stages::template Array<T>;

  explicit SsdSchedule(Stages& stages) : stages_(stages) {}

  // The detections of one image's outputs (encodings N x 4, logits N x (classes + 1),
  // anchors N x 4 on the stage set's side), best first. `params` must have passed
  // check(), the sizes validate_ssd_inputs (host/detect/ssd_postprocess.h).
  std::vector<SsdDetectionRecord> run(const Array<float>& encodings, const Array<float>& logits,
                                      const Array<float>& anchors, int anchor_count,
                                      int classes, const SsdPostprocessParams& params) {
    const int top_k = params.top_k_per_class;
    const int max_detections = params.max_detections;
    allocate(anchor_count, classes, top_k, max_detections);
    // Corner boxes of every anchor, clipped to the image.
    stages_.decode_boxes(encodings, anchors, anchor_count, params.box_scale, boxes_);
    // Each foreground class's score of every anchor.
    stages_.class_scores(logits, anchor_count, classes,
                         score_function_code(params.score_function), scores_);
    // Per class, the anchors scoring above the threshold (in any order).
    stages_.gather_candidates(scores_, anchor_count, classes, params.score_threshold,
                              candidates_, candidate_scores_, counts_);
    // Per class, the best top_k of them in a total order (score, then anchor).
    stages_.rank_candidates(candidates_, candidate_scores_, counts_, anchor_count, classes,
                            top_k, sorted_);
    // Which ranked candidate overlaps which lower-ranked one by more than the IoU limit.
    stages_.iou_mask(boxes_, sorted_, counts_, classes, top_k, params.iou_threshold, mask_);
    // Greedy NMS per class: one scan in rank order over the mask.
    stages_.nms_scan(mask_, sorted_, counts_, classes, top_k, kept_, kept_counts_);
    // The best max_detections survivors of all classes (score, class, anchor).
    stages_.rank_detections(scores_, boxes_, kept_, kept_counts_, anchor_count, classes, top_k,
                            max_detections, records_, record_count_);
    return stages_.download_records(records_, record_count_);
  }

 private:
  void allocate(int anchor_count, int classes, int top_k, int max_detections) {
    const int shape[4] = {anchor_count, classes, top_k, max_detections};
    if (allocated_ && std::equal(shape, shape + 4, shape_)) return;
    const size_t n = static_cast<size_t>(anchor_count);
    const size_t per_class = static_cast<size_t>(classes) * n;
    const size_t ranked = static_cast<size_t>(classes) * top_k;
    boxes_ = stages_.template array<float>(4 * n, "boxes");
    scores_ = stages_.template array<float>(per_class, "scores");
    candidates_ = stages_.template array<int>(per_class, "candidates");
    candidate_scores_ = stages_.template array<float>(per_class, "candidate scores");
    counts_ = stages_.template array<int>(classes, "candidate counts");
    sorted_ = stages_.template array<int>(ranked, "ranked candidates");
    mask_ = stages_.template array<std::uint32_t>(ranked * SSD_MASK_WORDS(top_k),
                                                  "suppression mask");
    kept_ = stages_.template array<int>(ranked, "survivors");
    kept_counts_ = stages_.template array<int>(classes, "survivor counts");
    records_ = stages_.template array<SsdDetectionRecord>(max_detections, "detections");
    record_count_ = stages_.template array<int>(1, "detection count");
    std::copy(shape, shape + 4, shape_);
    allocated_ = true;
  }

  Stages& stages_;
  bool allocated_ = false;
  int shape_[4] = {0, 0, 0, 0};
  Array<float> boxes_, scores_, candidate_scores_;
  Array<int> candidates_, counts_, sorted_, kept_, kept_counts_, record_count_;
  Array<std::uint32_t> mask_;
  Array<SsdDetectionRecord> records_;
};

}  // namespace flexsight

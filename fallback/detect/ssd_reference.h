#pragma once
// The scalar reference of SSD post-processing, one function per kernel of
// kernels/detect/ (same names, same arguments, outputs last and resized here), over the
// maths of kernels/detect/ssd_math.h. Its outputs are the kernels' bytes; where a
// kernel leaves part of an output unwritten (slots past a class's count), this path
// leaves zeros, and the comparisons look at the written part only. Layouts: see
// ssd_math.h. One thread: the whole chain takes about a millisecond for a trained
// detector's scores at 1917 x 24 (docs/detect.md).
#include <cstdint>
#include <vector>

#include "kernels/detect/ssd_math.h"

namespace flexsight {

static_assert(sizeof(SsdDetectionRecord) == 28, "OpenCL C lays the record out in 28 bytes");

// The box coder's scale factors (TF OD API FasterRcnnBoxCoder scale_factors: y, x, h, w).
struct SsdBoxScale {
  float y = 10.0f;
  float x = 10.0f;
  float h = 5.0f;
  float w = 5.0f;
};

// boxes (N x 4, corners) of every anchor (ssd_decode_box).
void decode_boxes(const std::vector<float>& encodings, const std::vector<float>& anchors,
                  int anchor_count, const SsdBoxScale& scale, std::vector<float>& boxes);

// scores (C x N, class-major) of the logits (N x (C + 1)) by SSD_SCORE_SIGMOID or
// SSD_SCORE_SOFTMAX.
void class_scores(const std::vector<float>& logits, int anchor_count, int classes,
                  int score_function, std::vector<float>& scores);

// Per class, the anchors whose score is above the threshold and their scores (C x N,
// class c's from c * N), in anchor order (the kernel's order is arbitrary; the next
// stage's result is not), and their number per class.
void gather_candidates(const std::vector<float>& scores, int anchor_count, int classes,
                       float score_threshold, std::vector<int>& candidates,
                       std::vector<float>& candidate_scores, std::vector<int>& counts);

// Per class, the first min(count, top_k) candidates' anchors by ssd_candidate_before
// (C x top_k). The kernel counts each candidate's rank; this sorts.
void rank_candidates(const std::vector<int>& candidates,
                     const std::vector<float>& candidate_scores, const std::vector<int>& counts,
                     int anchor_count, int classes, int top_k, std::vector<int>& sorted);

// The suppression mask (C x top_k rows of SSD_MASK_WORDS(top_k) words; ssd_mask_word).
void iou_mask(const std::vector<float>& boxes, const std::vector<int>& sorted,
              const std::vector<int>& counts, int classes, int top_k, float iou_threshold,
              std::vector<std::uint32_t>& mask);

// Greedy NMS per class by its mask (ssd_nms_scan_class): survivors' anchors in rank
// order (C x top_k) and their number per class.
void nms_scan(const std::vector<std::uint32_t>& mask, const std::vector<int>& sorted,
              const std::vector<int>& counts, int classes, int top_k, std::vector<int>& kept,
              std::vector<int>& kept_counts);

// The first min(survivors, max_detections) survivors of all classes by
// ssd_detection_before as records (max_detections slots), and their number. The kernel
// counts ranks; this sorts.
void rank_detections(const std::vector<float>& scores, const std::vector<float>& boxes,
                     const std::vector<int>& kept, const std::vector<int>& kept_counts,
                     int anchor_count, int classes, int top_k, int max_detections,
                     std::vector<SsdDetectionRecord>& records, std::vector<int>& record_count);

}  // namespace flexsight

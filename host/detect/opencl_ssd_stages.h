#pragma once
// One method per kernel of kernels/detect/, each the device twin of the reference
// function of fallback/detect/ssd_reference.h with the same name and arguments, and
// the stage set of the one schedule (host/detect/ssd_schedule.h). The tests compare
// every stage with its reference byte for byte. Outputs are allocated by the caller and
// must hold the stage's elements (checked); nothing past them is written.
#include <cstdint>
#include <vector>

#include "fallback/detect/ssd_reference.h"
#include "host/runtime/kernel_profiler.h"

namespace flexsight::opencl {

class OpenClSsdStages {
 public:
  template <class T>
  using Array = Buffer<T>;

  // Builds the programs (or takes them from the context's cache). `profiler` (may be
  // null) receives the event of every launch.
  explicit OpenClSsdStages(Context& context, KernelProfiler* profiler = nullptr);

  Context& context() { return context_; }

  template <class T>
  Array<T> array(size_t count, const char* what) {
    return Buffer<T>(context_, count, what);
  }
  Array<float> upload(const float* values, size_t count, const char* what) {
    Buffer<float> buffer(context_, count, what);
    buffer.write(values, count);
    return buffer;
  }
  // The first record_count[0] records (two reads).
  std::vector<SsdDetectionRecord> download_records(const Buffer<SsdDetectionRecord>& records,
                                                   const Buffer<int>& record_count);

  // ssd_decode.cl. class_scores launches sigmoid_scores or softmax_scores.
  void decode_boxes(const Buffer<float>& encodings, const Buffer<float>& anchors,
                    int anchor_count, const SsdBoxScale& scale, Buffer<float>& boxes);
  void class_scores(const Buffer<float>& logits, int anchor_count, int classes,
                    int score_function, Buffer<float>& scores);
  // ssd_nms.cl. gather_candidates zeroes `counts` first; its candidates come in any
  // order (rank_candidates' result does not depend on it).
  void gather_candidates(const Buffer<float>& scores, int anchor_count, int classes,
                         float score_threshold, Buffer<int>& candidates,
                         Buffer<float>& candidate_scores, Buffer<int>& counts);
  void rank_candidates(const Buffer<int>& candidates, const Buffer<float>& candidate_scores,
                       const Buffer<int>& counts, int anchor_count, int classes, int top_k,
                       Buffer<int>& sorted);
  void iou_mask(const Buffer<float>& boxes, const Buffer<int>& sorted, const Buffer<int>& counts,
                int classes, int top_k, float iou_threshold, Buffer<std::uint32_t>& mask);
  void nms_scan(const Buffer<std::uint32_t>& mask, const Buffer<int>& sorted,
                const Buffer<int>& counts, int classes, int top_k, Buffer<int>& kept,
                Buffer<int>& kept_counts);
  void rank_detections(const Buffer<float>& scores, const Buffer<float>& boxes,
                       const Buffer<int>& kept, const Buffer<int>& kept_counts, int anchor_count,
                       int classes, int top_k, int max_detections,
                       Buffer<SsdDetectionRecord>& records, Buffer<int>& record_count);

 private:
  void launch(Kernel& kernel, size_t width, size_t height);
  void launch_linear(Kernel& kernel, int count);

  Context& context_;
  KernelProfiler* profiler_;
  Kernel decode_boxes_, sigmoid_scores_, softmax_scores_, gather_candidates_, rank_candidates_, iou_mask_,
      nms_scan_, rank_detections_;
};

}  // namespace flexsight::opencl

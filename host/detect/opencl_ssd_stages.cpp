#include "host/detect/opencl_ssd_stages.h"

#include <stdexcept>
#include <string>

#include "generated/detect_kernel_sources.h"

namespace flexsight::opencl {
namespace {

namespace src = kernel_sources::detect;

void require_top_k(int top_k, const char* stage) {
  if (top_k < 1 || top_k > SSD_MAX_TOP_K) {
    throw std::invalid_argument(std::string(stage) + ": top_k must be in 1.." +
                                std::to_string(SSD_MAX_TOP_K) + ", got " +
                                std::to_string(top_k));
  }
}

long long product(long long a, long long b) { return a * b; }

}  // namespace

OpenClSsdStages::OpenClSsdStages(Context& context, KernelProfiler* profiler)
    : context_(context), profiler_(profiler),
      decode_boxes_(Kernel(context, src::ssd_decode, "decode_boxes")),
      sigmoid_scores_(Kernel(context, src::ssd_decode, "sigmoid_scores")),
      softmax_scores_(Kernel(context, src::ssd_decode, "softmax_scores")),
      gather_candidates_(Kernel(context, src::ssd_nms, "gather_candidates")),
      rank_candidates_(Kernel(context, src::ssd_nms, "rank_candidates")),
      iou_mask_(Kernel(context, src::ssd_nms, "iou_mask")),
      nms_scan_(Kernel(context, src::ssd_nms, "nms_scan")),
      rank_detections_(Kernel(context, src::ssd_nms, "rank_detections")) {}

void OpenClSsdStages::launch(Kernel& kernel, size_t width, size_t height) {
  launch_profiled(kernel, width, height, profiler_);
}

// SSD_LINEAR_ROWS rows of ceil(count / rows) items (ssd_linear_item): a launch over
// (count, 1) would leave all but the first row of every 16 x 4 work group idle.
void OpenClSsdStages::launch_linear(Kernel& kernel, int count) {
  launch(kernel, (static_cast<size_t>(count) + SSD_LINEAR_ROWS - 1) / SSD_LINEAR_ROWS,
         SSD_LINEAR_ROWS);
}

std::vector<SsdDetectionRecord> OpenClSsdStages::download_records(
    const Buffer<SsdDetectionRecord>& records, const Buffer<int>& record_count) {
  const int count = record_count.read(0, 1)[0];
  if (count < 0 || static_cast<size_t>(count) > records.size()) {
    throw std::logic_error("rank_detections reported " + std::to_string(count) +
                           " detections for " + std::to_string(records.size()) + " slots");
  }
  return count == 0 ? std::vector<SsdDetectionRecord>() : records.read(0, count);
}

void OpenClSsdStages::decode_boxes(const Buffer<float>& encodings, const Buffer<float>& anchors,
                                   int anchor_count, const SsdBoxScale& scale,
                                   Buffer<float>& boxes) {
  require_size(encodings, product(4, anchor_count), "decode_boxes");
  require_size(anchors, product(4, anchor_count), "decode_boxes");
  require_size(boxes, product(4, anchor_count), "decode_boxes");
  decode_boxes_.set_args(encodings, anchors, anchor_count, scale.y, scale.x, scale.h, scale.w,
                         boxes);
  launch_linear(decode_boxes_, anchor_count);
}

void OpenClSsdStages::class_scores(const Buffer<float>& logits, int anchor_count, int classes,
                                   int score_function, Buffer<float>& scores) {
  require_size(logits, product(anchor_count, classes + 1), "class_scores");
  require_size(scores, product(classes, anchor_count), "class_scores");
  if (score_function == SSD_SCORE_SOFTMAX) {
    softmax_scores_.set_args(logits, anchor_count, classes, scores);
    launch_linear(softmax_scores_, anchor_count);
  } else {
    sigmoid_scores_.set_args(logits, anchor_count, classes, scores);
    launch(sigmoid_scores_, anchor_count, classes);
  }
}

void OpenClSsdStages::gather_candidates(const Buffer<float>& scores, int anchor_count,
                                        int classes, float score_threshold,
                                        Buffer<int>& candidates, Buffer<float>& candidate_scores,
                                        Buffer<int>& counts) {
  require_size(scores, product(classes, anchor_count), "gather_candidates");
  require_size(candidates, product(classes, anchor_count), "gather_candidates");
  require_size(candidate_scores, product(classes, anchor_count), "gather_candidates");
  require_size(counts, classes, "gather_candidates");
  // Only the classes' counters: the buffer may be longer (the tests' guard region).
  const int zero = 0;
  fill_bytes(context_, counts.get(), &zero, sizeof zero, classes * sizeof(int), counts.what());
  gather_candidates_.set_args(scores, anchor_count, classes, score_threshold, candidates,
                              candidate_scores, counts);
  launch(gather_candidates_, anchor_count, classes);
}

void OpenClSsdStages::rank_candidates(const Buffer<int>& candidates,
                                      const Buffer<float>& candidate_scores,
                                      const Buffer<int>& counts, int anchor_count, int classes,
                                      int top_k, Buffer<int>& sorted) {
  require_top_k(top_k, "rank_candidates");
  require_size(candidates, product(classes, anchor_count), "rank_candidates");
  require_size(candidate_scores, product(classes, anchor_count), "rank_candidates");
  require_size(counts, classes, "rank_candidates");
  require_size(sorted, product(classes, top_k), "rank_candidates");
  rank_candidates_.set_args(candidates, candidate_scores, counts, anchor_count, classes, top_k,
                            sorted);
  launch(rank_candidates_, anchor_count, classes);
}

void OpenClSsdStages::iou_mask(const Buffer<float>& boxes, const Buffer<int>& sorted,
                               const Buffer<int>& counts, int classes, int top_k,
                               float iou_threshold, Buffer<std::uint32_t>& mask) {
  require_top_k(top_k, "iou_mask");
  require_size(sorted, product(classes, top_k), "iou_mask");
  require_size(counts, classes, "iou_mask");
  require_size(mask, product(classes, top_k) * SSD_MASK_WORDS(top_k), "iou_mask");
  iou_mask_.set_args(boxes, sorted, counts, classes, top_k, iou_threshold, mask);
  launch(iou_mask_, top_k, classes);
}

void OpenClSsdStages::nms_scan(const Buffer<std::uint32_t>& mask, const Buffer<int>& sorted,
                               const Buffer<int>& counts, int classes, int top_k,
                               Buffer<int>& kept, Buffer<int>& kept_counts) {
  require_top_k(top_k, "nms_scan");
  require_size(mask, product(classes, top_k) * SSD_MASK_WORDS(top_k), "nms_scan");
  require_size(sorted, product(classes, top_k), "nms_scan");
  require_size(counts, classes, "nms_scan");
  require_size(kept, product(classes, top_k), "nms_scan");
  require_size(kept_counts, classes, "nms_scan");
  nms_scan_.set_args(mask, sorted, counts, classes, top_k, kept, kept_counts);
  launch_linear(nms_scan_, classes);
}

void OpenClSsdStages::rank_detections(const Buffer<float>& scores, const Buffer<float>& boxes,
                                      const Buffer<int>& kept, const Buffer<int>& kept_counts,
                                      int anchor_count, int classes, int top_k,
                                      int max_detections, Buffer<SsdDetectionRecord>& records,
                                      Buffer<int>& record_count) {
  require_top_k(top_k, "rank_detections");
  require_size(scores, product(classes, anchor_count), "rank_detections");
  require_size(boxes, product(4, anchor_count), "rank_detections");
  require_size(kept, product(classes, top_k), "rank_detections");
  require_size(kept_counts, classes, "rank_detections");
  require_size(records, max_detections, "rank_detections");
  require_size(record_count, 1, "rank_detections");
  rank_detections_.set_args(scores, boxes, kept, kept_counts, anchor_count, classes, top_k,
                            max_detections, records, record_count);
  launch(rank_detections_, top_k, classes);
}

}  // namespace flexsight::opencl

/* The first two stages of SSD post-processing (reference: fallback/detect/ssd_reference.h):
 * decode_boxes and class_scores. */
#include "ssd_kernel_support.h"

/* Corner boxes of every anchor (ssd_decode_box). */
__kernel void decode_boxes(const __global float* encodings, const __global float* anchors,
                           int anchor_count, float scale_y, float scale_x, float scale_h,
                           float scale_w, __global float* boxes) {
  int anchor;
  if (!ssd_linear_item(anchor_count, &anchor)) return;
  SsdBox box = ssd_decode_box(encodings + anchor * 4, anchors + anchor * 4, scale_y, scale_x,
                              scale_h, scale_w);
  boxes[anchor * 4 + 0] = box.x_min;
  boxes[anchor * 4 + 1] = box.y_min;
  boxes[anchor * 4 + 2] = box.x_max;
  boxes[anchor * 4 + 3] = box.y_max;
}

/* The class_scores stage, written class-major (scores[c * N + anchor]) so that the
 * per-class stages read a class contiguously; the host launches one of two kernels.
 * Sigmoid: one work item per (anchor, class), a body without loops that a CPU driver
 * vectorises across work items. */
__kernel void sigmoid_scores(const __global float* logits, int anchor_count, int classes,
                             __global float* scores) {
  int anchor, c;
  if (!ssd_work_item(anchor_count, classes, &anchor, &c)) return;
  scores[c * anchor_count + anchor] = ssd_sigmoid_score(logits[anchor * (classes + 1) + c + 1]);
}

/* Softmax: one work item per anchor, which needs the whole row's max and exp sum. */
__kernel void softmax_scores(const __global float* logits, int anchor_count, int classes,
                             __global float* scores) {
  int anchor;
  if (!ssd_linear_item(anchor_count, &anchor)) return;
  ssd_softmax_scores(logits + anchor * (classes + 1), classes, scores + anchor, anchor_count);
}

/*
 * The mathematics of SSD post-processing, shared verbatim by the scalar reference path
 * (fallback/detect/, compiled as C++) and the kernels (the .cl files of kernels/detect/,
 * compiled as OpenCL C), so that both give the same bytes:
 *   - exp, sigmoid and softmax from basic float operations only (no built-in
 *     transcendental function, whose rounding differs between devices and libms);
 *   - box decoding (the TensorFlow Object Detection API's FasterRcnnBoxCoder), IoU;
 *   - the orders that make the selection independent of the work-item order: a strict
 *     total order on candidates (score, then anchor index) and on detections (score,
 *     class, anchor), by which the kernels count ranks and the reference sorts; the
 *     suppression mask and the ordered scan over it.
 *
 * Same rules as kernels/stereo/pms_math.h: contraction off on both compilers, only
 * exact or correctly rounded operations (+ - * /, floor, comparisons), each expression
 * written in the order it must be evaluated. Where IEEE 754 leaves a choice (the bits
 * of a NaN, fmin/fmax of -0 and +0), comparisons pin the result down.
 *
 * Layouts (all flat arrays, N anchors, C foreground classes):
 *   encodings  N x 4   (ty, tx, th, tw) as the network outputs them
 *   logits     N x (C + 1), column 0 the background
 *   anchors    N x 4   (ycenter, xcenter, height, width), normalised to [0, 1]
 *   boxes      N x 4   (x_min, y_min, x_max, y_max), normalised, clipped to [0, 1]
 *   scores     C x N   class-major: scores[c * N + anchor], c the foreground class 0..C-1
 */
#ifndef FLEXSIGHT_SSD_MATH_H
#define FLEXSIGHT_SSD_MATH_H

#include "../common/portability.h"

#ifdef __OPENCL_VERSION__
#define SSD_FLOAT_FROM_BITS(bits) as_float((uint)(bits))
#else
#include <cstring>
inline float ssd_float_from_bits(fs_u32 bits) {
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}
#define SSD_FLOAT_FROM_BITS(bits) ssd_float_from_bits(bits)
#endif

/* Score functions (SsdPostprocessParams::score_function): a sigmoid per class logit
 * (focal-loss training) or a softmax over the background and the classes. */
#define SSD_SCORE_SIGMOID 0
#define SSD_SCORE_SOFTMAX 1

/* Candidates kept per class before NMS at most: the suppression mask of a class is
 * top_k x top_k bits, its rows SSD_MASK_WORDS(top_k) 32-bit words, and the ordered
 * scan keeps one row of "removed" bits in private memory (32 words). */
#define SSD_MAX_TOP_K 1024
#define SSD_MASK_WORDS(top_k) (((top_k) + 31) / 32)

/* Rows of the launches over a list of items (anchors, classes): ceil(count / 4) items
 * a row, so that the runtime's work groups (16 x 4, host/runtime/cl_kernel.cpp) have
 * work in every row (ssd_linear_item, OpenClSsdStages::launch_linear). */
#define SSD_LINEAR_ROWS 4

/* One detection as the last stage writes it (host/detect/detection.h converts it):
 * seven 4-byte fields, so OpenCL C and C++ lay it out alike (28 bytes, no padding). */
typedef struct SsdDetectionRecord {
  int class_id; /* foreground class, 0..C-1 (logit column class_id + 1) */
  int anchor;   /* the anchor it was decoded from */
  float score;
  float box[4]; /* x_min, y_min, x_max, y_max, normalised */
} SsdDetectionRecord;

typedef struct SsdBox {
  float x_min, y_min, x_max, y_max;
} SsdBox;

/* ------------------------------------------------------------------ exp and friends */

/* exp(x) in float from + - * and floor (Cody and Waite's reduction, Moshier's Cephes
 * expf polynomial): x = n ln2 + r with |r| <= ln2/2, ln2 split in a part with 9
 * significant bits (n * 0.693359375 is exact for |n| <= 128) and the rest; e^r by a
 * degree-7 polynomial; then scaled by 2^n, built from its bits in two halves so that
 * neither factor leaves the normal range. Measured against std::exp in double on every
 * float of [-87, 88]: at most 0.99 ulp, relative error at most 8.2e-8 (the test,
 * tests/detect/test_ssd_math.cpp, checks every 61st float). Below -87 it returns 0:
 * the true value, under 1.7e-38, turns subnormal just below -87.3, and devices may
 * flush subnormals, so the cut is where every result is still normal. Above 89 +inf;
 * NaN stays NaN. */
FS_INLINE float ssd_exp(float x) {
  /* Without branches (selects only), so that a CPU driver can vectorise it across
   * work items: the core runs on x limited to [-87, 89] (0 for NaN), the ends are
   * chosen after. */
  float xc = x == x ? x : 0.0f;
  xc = xc > 89.0f ? 89.0f : xc;
  xc = xc < -87.0f ? -87.0f : xc;
  float n = FS_FLOOR(xc * 1.44269504088896341f + 0.5f);
  float r = xc - n * 0.693359375f;
  r = r - n * -2.12194440e-4f;
  float z = r * r;
  float p = 1.9875691500e-4f;
  p = p * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  float y = p * z + r + 1.0f;
  int k = (int)n;
  int k_half = k / 2;
  int k_rest = k - k_half;
  y = y * SSD_FLOAT_FROM_BITS((fs_u32)(k_half + 127) << 23);
  y = y * SSD_FLOAT_FROM_BITS((fs_u32)(k_rest + 127) << 23);
  y = x > 89.0f ? SSD_FLOAT_FROM_BITS(0x7f800000u) : y;
  y = x < -87.0f ? 0.0f : y;
  return x == x ? y : x;
}

/* 1 / (1 + e^-x): 0 below x = -89, 1 where e^-x is below half an ulp of 1. */
FS_INLINE float ssd_sigmoid(float x) { return 1.0f / (1.0f + ssd_exp(-x)); }

/* A score that is NaN (from a NaN logit) becomes 0, never a detection: the sign and
 * payload of a NaN are not fixed by IEEE 754 and do differ between the compilers. */
FS_INLINE float ssd_score_or_zero(float score) { return score == score ? score : 0.0f; }

/* Sigmoid score of one class logit. */
FS_INLINE float ssd_sigmoid_score(float logit) { return ssd_score_or_zero(ssd_sigmoid(logit)); }

/* The largest of a row's `count` logits, by comparisons (fmax may return either zero
 * of fmax(-0, +0); a comparison has one answer). */
FS_INLINE float ssd_row_max(const FS_GLOBAL float* row, int count) {
  float m = row[0];
  for (int i = 1; i < count; ++i) m = row[i] > m ? row[i] : m;
  return m;
}

/* Softmax scores of one anchor's logit row (the background, then `classes` classes):
 * class c's to out[c * stride]. One exp per logit, e^(logit - row max), the classes'
 * stored in `out` on the way; their sum is added in column order (one fixed order is
 * what makes it the same on both paths), then each is divided by it. A NaN logit makes
 * the whole row NaN, hence 0. */
FS_INLINE void ssd_softmax_scores(const FS_GLOBAL float* row, int classes, FS_GLOBAL float* out,
                                  int stride) {
  float row_max = ssd_row_max(row, classes + 1);
  float sum = ssd_exp(row[0] - row_max);
  for (int c = 0; c < classes; ++c) {
    float e = ssd_exp(row[c + 1] - row_max);
    out[c * stride] = e;
    sum = sum + e;
  }
  for (int c = 0; c < classes; ++c) out[c * stride] = ssd_score_or_zero(out[c * stride] / sum);
}

/* ---------------------------------------------------------------------- boxes */

/* v limited to [0, 1] by comparisons: NaN and -0 give +0 (fmin/fmax may keep either
 * zero, and a NaN's bits are not portable). */
FS_INLINE float ssd_clip_unit(float v) { return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; }

/* The TF OD API's FasterRcnnBoxCoder.decode: the encoding divided by the scale factors
 * (10, 10, 5, 5 for SSD: the "variances" 0.1 and 0.2), centre moved by a fraction of
 * the anchor's size, size scaled by e^(th), e^(tw); corners clipped to [0, 1] (TF clips
 * to the image window after decoding). Written in TF's order of operations. */
FS_INLINE SsdBox ssd_decode_box(const FS_GLOBAL float* encoding, const FS_GLOBAL float* anchor,
                                float scale_y, float scale_x, float scale_h, float scale_w) {
  float ty = encoding[0] / scale_y;
  float tx = encoding[1] / scale_x;
  float th = encoding[2] / scale_h;
  float tw = encoding[3] / scale_w;
  float ycenter_a = anchor[0];
  float xcenter_a = anchor[1];
  float ha = anchor[2];
  float wa = anchor[3];
  float w = ssd_exp(tw) * wa;
  float h = ssd_exp(th) * ha;
  float ycenter = ty * ha + ycenter_a;
  float xcenter = tx * wa + xcenter_a;
  SsdBox box;
  box.x_min = ssd_clip_unit(xcenter - w / 2.0f);
  box.y_min = ssd_clip_unit(ycenter - h / 2.0f);
  box.x_max = ssd_clip_unit(xcenter + w / 2.0f);
  box.y_max = ssd_clip_unit(ycenter + h / 2.0f);
  return box;
}

FS_INLINE SsdBox ssd_load_box(const FS_GLOBAL float* boxes, int anchor) {
  SsdBox box;
  box.x_min = boxes[anchor * 4 + 0];
  box.y_min = boxes[anchor * 4 + 1];
  box.x_max = boxes[anchor * 4 + 2];
  box.y_max = boxes[anchor * 4 + 3];
  return box;
}

/* Intersection over union; 0 for disjoint or empty boxes (a box clipped away to a line
 * on the border suppresses nothing). */
FS_INLINE float ssd_iou(SsdBox a, SsdBox b) {
  float inter_w = FS_FMIN(a.x_max, b.x_max) - FS_FMAX(a.x_min, b.x_min);
  float inter_h = FS_FMIN(a.y_max, b.y_max) - FS_FMAX(a.y_min, b.y_min);
  if (!(inter_w > 0.0f) || !(inter_h > 0.0f)) return 0.0f;
  float inter = inter_w * inter_h;
  float area_a = (a.x_max - a.x_min) * (a.y_max - a.y_min);
  float area_b = (b.x_max - b.x_min) * (b.y_max - b.y_min);
  float union_area = area_a + area_b - inter;
  return union_area > 0.0f ? inter / union_area : 0.0f;
}

/* ------------------------------------------------------------- deterministic order */

/* Candidates of one class: higher score first, the lower anchor index on equal scores.
 * A strict total order (anchors are distinct), so every rank is unique. */
FS_INLINE int ssd_candidate_before(float score_a, int anchor_a, float score_b, int anchor_b) {
  return score_a > score_b || (score_a == score_b && anchor_a < anchor_b);
}

/* Detections of all classes: higher score first, then the lower class, then the lower
 * anchor. */
FS_INLINE int ssd_detection_before(float score_a, int class_a, int anchor_a, float score_b,
                                   int class_b, int anchor_b) {
  if (score_a != score_b) return score_a > score_b;
  if (class_a != class_b) return class_a < class_b;
  return anchor_a < anchor_b;
}

/* Word `word` of row i of a class's suppression mask: bit b set when candidate
 * j = 32 word + b ranks after i (j > i), is one of the class's `count` ranked
 * candidates, and overlaps i by IoU > iou_threshold. `sorted` holds the class's
 * candidates' anchors by rank. */
FS_INLINE fs_u32 ssd_mask_word(const FS_GLOBAL float* boxes, const FS_GLOBAL int* sorted,
                               int count, int i, int word, float iou_threshold) {
  fs_u32 bits = 0u;
  if (i >= count) return bits;
  SsdBox box_i = ssd_load_box(boxes, sorted[i]);
  for (int b = 0; b < 32; ++b) {
    int j = word * 32 + b;
    if (j <= i || j >= count) continue;
    if (ssd_iou(box_i, ssd_load_box(boxes, sorted[j])) > iou_threshold) bits |= 1u << b;
  }
  return bits;
}

/* Greedy NMS of one class as one ordered scan over its mask: a candidate survives
 * unless a survivor ranked before it removed it; a survivor removes the candidates its
 * mask row marks. Writes the survivors' anchors to `kept` in rank order and returns
 * their number. */
FS_INLINE int ssd_nms_scan_class(const FS_GLOBAL fs_u32* mask, const FS_GLOBAL int* sorted,
                                 int count, int words, FS_GLOBAL int* kept) {
  fs_u32 removed[SSD_MASK_WORDS(SSD_MAX_TOP_K)];
  for (int w = 0; w < words; ++w) removed[w] = 0u;
  int kept_count = 0;
  for (int i = 0; i < count; ++i) {
    if ((removed[i / 32] >> (i % 32)) & 1u) continue;
    kept[kept_count] = sorted[i];
    kept_count = kept_count + 1;
    for (int w = i / 32; w < words; ++w) removed[w] |= mask[i * words + w];
  }
  return kept_count;
}

#endif /* FLEXSIGHT_SSD_MATH_H */

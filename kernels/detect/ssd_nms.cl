/* Candidate selection and per-class NMS (reference: fallback/detect/ssd_reference.h).
 * No result depends on the order in which work items run: candidates are gathered in
 * any order (an atomic counter per class), then each finds its rank in a strict total
 * order (score, then anchor) and writes itself there; the suppression mask is a pure
 * function of the ranked list; one work item per class scans it in rank order; the
 * survivors of all classes are ranked by (score, class, anchor), each class's list
 * being in that order already. */
#include "ssd_kernel_support.h"

/* Rank of candidate i among a class's `count` candidates (anchors and their scores, in
 * any order): how many come before it. The loop runs over all of them without an early
 * exit, a count a CPU driver vectorises and a GPU runs without divergence. The
 * reference sorts by the same order instead; a strict total order gives one result
 * either way. */
inline int ssd_candidate_rank(const __global int* anchors, const __global float* scores,
                              int count, int i) {
  float score = scores[i];
  int anchor = anchors[i];
  int rank = 0;
  for (int j = 0; j < count; ++j) rank += ssd_candidate_before(scores[j], anchors[j], score, anchor);
  return rank;
}

/* How many of class `other`'s survivors come before detection (score, c, ...) of
 * another class by ssd_detection_before. A class's survivors are in its candidates'
 * order (score down, anchor up), so those are a prefix of its list: the ones scoring
 * higher, and the ones scoring equal when `other` is the lower class. A binary search
 * finds its length. */
inline int ssd_survivors_before(const __global float* other_scores,
                                const __global int* other_kept, int count, int other,
                                float score, int c) {
  int low = 0;
  int high = count;
  while (low < high) {
    int middle = low + (high - low) / 2;
    float s = other_scores[other_kept[middle]];
    if (s > score || (s == score && other < c)) {
      low = middle + 1;
    } else {
      high = middle;
    }
  }
  return low;
}

/* Rank of survivor j of class c among the survivors of every class (kept: classes x
 * top_k anchors, kept_counts per class) by ssd_detection_before: j within its own
 * class (its list is in that order), plus the prefixes of the others. */
inline int ssd_detection_rank(const __global float* scores, const __global int* kept,
                              const __global int* kept_counts, int anchors, int classes,
                              int top_k, int c, int j, float score) {
  int rank = j;
  for (int other = 0; other < classes; ++other) {
    if (other == c) continue;
    rank += ssd_survivors_before(scores + other * anchors, kept + other * top_k,
                                 kept_counts[other], other, score, c);
  }
  return rank;
}

/* Appends (anchor, score) to the candidates of class c when score > threshold. Items:
 * (anchor, class). `counts` must be zero before the launch. */
__kernel void gather_candidates(const __global float* scores, int anchor_count, int classes,
                                float score_threshold, __global int* candidates,
                                __global float* candidate_scores, __global int* counts) {
  int anchor, c;
  if (!ssd_work_item(anchor_count, classes, &anchor, &c)) return;
  float score = scores[c * anchor_count + anchor];
  if (!(score > score_threshold)) return;
  int slot = atomic_inc(counts + c);
  candidates[c * anchor_count + slot] = anchor;
  candidate_scores[c * anchor_count + slot] = score;
}

/* Writes each candidate's anchor at its rank when the rank is below top_k: sorted[c *
 * top_k + rank]. Items: (candidate slot, class). Slots at or past min(count, top_k)
 * of a class are left as they were. */
__kernel void rank_candidates(const __global int* candidates,
                              const __global float* candidate_scores, const __global int* counts,
                              int anchor_count, int classes, int top_k, __global int* sorted) {
  int i, c;
  if (!ssd_work_item(anchor_count, classes, &i, &c) || i >= counts[c]) return;
  const __global int* anchors = candidates + c * anchor_count;
  const __global float* scores = candidate_scores + c * anchor_count;
  int rank = ssd_candidate_rank(anchors, scores, counts[c], i);
  if (rank < top_k) sorted[c * top_k + rank] = anchors[i];
}

/* The suppression mask, every row of every class (rows past a class's candidates are
 * zero): mask[(c * top_k + i) * words + w]. Items: (row i, class). */
__kernel void iou_mask(const __global float* boxes, const __global int* sorted,
                       const __global int* counts, int classes, int top_k, float iou_threshold,
                       __global uint* mask) {
  int i, c;
  if (!ssd_work_item(top_k, classes, &i, &c)) return;
  int count = min(counts[c], top_k);
  int words = SSD_MASK_WORDS(top_k);
  for (int w = 0; w < words; ++w) {
    mask[(c * top_k + i) * words + w] =
        ssd_mask_word(boxes, sorted + c * top_k, count, i, w, iou_threshold);
  }
}

/* Greedy NMS of each class by its mask: survivors' anchors in rank order to kept[c *
 * top_k ...], their number to kept_counts[c]. One work item per class
 * (ssd_linear_item). */
__kernel void nms_scan(const __global uint* mask, const __global int* sorted,
                       const __global int* counts, int classes, int top_k, __global int* kept,
                       __global int* kept_counts) {
  int c;
  if (!ssd_linear_item(classes, &c)) return;
  int words = SSD_MASK_WORDS(top_k);
  kept_counts[c] = ssd_nms_scan_class(mask + c * top_k * words, sorted + c * top_k,
                                      min(counts[c], top_k), words, kept + c * top_k);
}

/* The survivors of all classes ranked by (score, class, anchor); each of rank below
 * max_detections writes its record there, and item (0, 0) the number of records,
 * min(survivors, max_detections). Items: (survivor j, class). Records past that
 * number are left as they were. */
__kernel void rank_detections(const __global float* scores, const __global float* boxes,
                              const __global int* kept, const __global int* kept_counts,
                              int anchor_count, int classes, int top_k, int max_detections,
                              __global SsdDetectionRecord* records, __global int* record_count) {
  int j, c;
  if (!ssd_work_item(top_k, classes, &j, &c)) return;
  if (j == 0 && c == 0) {
    int total = 0;
    for (int other = 0; other < classes; ++other) total += kept_counts[other];
    record_count[0] = min(total, max_detections);
  }
  if (j >= kept_counts[c]) return;
  int anchor = kept[c * top_k + j];
  float score = scores[c * anchor_count + anchor];
  int rank = ssd_detection_rank(scores, kept, kept_counts, anchor_count, classes, top_k, c, j,
                                score);
  if (rank >= max_detections) return;
  __global SsdDetectionRecord* record = records + rank;
  record->class_id = c;
  record->anchor = anchor;
  record->score = score;
  SsdBox box = ssd_load_box(boxes, anchor);
  record->box[0] = box.x_min;
  record->box[1] = box.y_min;
  record->box[2] = box.x_max;
  record->box[3] = box.y_max;
}

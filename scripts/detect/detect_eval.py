"""Detections from the raw SSD outputs, and average precision at IoU 0.5: a quick check of a
training run in Python, and a reference for the C++ decoder.

Decoding (TF OD API post-processing, as the C++ one): boxes from the encodings and the anchors,
clipped to the image, scores = softmax over the C + 1 logits (background at 0), per class the
boxes above `score_threshold`, non-maximum suppression per class of the boxes overlapping a better
one by IoU above `nms_iou`, the `max_detections` best overall.
tests/detect/python/test_detect_eval_matches_cpp.py checks both against `flexsight detect` and
`flexsight eval-det`.
AP: per class, detections sorted by score, greedy matching to unmatched ground truth at
IoU >= 0.5, all-point interpolated precision (the VOC 2010+ / COCO rule at one threshold);
the mean is over the classes that have ground truth.

    python3 -m detect.detect_eval --checkpoint RUN/model.pt --data DATA [--limit 200]
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
import torch

from . import anchors as anc
from .coco_set import CocoSet
from .export_onnx import load_checkpoint


def nms(boxes: np.ndarray, scores: np.ndarray, iou_threshold: float) -> np.ndarray:
    """Indices kept, best first; boxes are corners (ymin, xmin, ymax, xmax)."""
    order = np.argsort(-scores, kind="stable")
    keep = []
    while order.size:
        i = order[0]
        keep.append(i)
        if order.size == 1:
            break
        ious = anc.iou(boxes[i:i + 1], boxes[order[1:]])[0]
        order = order[1:][ious <= iou_threshold]  # IoU above the threshold suppresses, as in C++
    return np.array(keep, np.int64)


def decode_detections(box_encodings: np.ndarray, class_logits: np.ndarray, anchors: np.ndarray,
                      score_threshold: float = 0.01, nms_iou: float = 0.6,
                      max_detections: int = 100):
    """One image: [A, 4] encodings and [A, C + 1] logits -> (corners [D, 4] normalised,
    scores [D], classes [D] in 1..C)."""
    z = class_logits - class_logits.max(1, keepdims=True)
    p = np.exp(z)
    p /= p.sum(1, keepdims=True)
    boxes = np.clip(anc.corners(anc.decode(box_encodings, anchors)), 0.0, 1.0)  # as TF and C++ clip
    out_b, out_s, out_c = [], [], []
    for c in range(1, p.shape[1]):
        idx = np.nonzero(p[:, c] > score_threshold)[0]
        if idx.size == 0:
            continue
        keep = idx[nms(boxes[idx], p[idx, c], nms_iou)]
        out_b.append(boxes[keep])
        out_s.append(p[keep, c])
        out_c.append(np.full(keep.size, c))
    if not out_b:
        return np.zeros((0, 4)), np.zeros(0), np.zeros(0, np.int64)
    b, s, c = np.concatenate(out_b), np.concatenate(out_s), np.concatenate(out_c)
    top = np.argsort(-s, kind="stable")[:max_detections]
    return b[top], s[top], c[top]


def average_precision_50(detections, ground_truth, num_classes: int):
    """detections, ground_truth: per image (corners, [scores,] classes). Returns (mAP, {class: AP})."""
    aps = {}
    for c in range(1, num_classes + 1):
        n_gt = sum(int((g[1] == c).sum()) for g in ground_truth)
        if n_gt == 0:
            continue
        records = []  # (score, image, box)
        for i, (b, s, k) in enumerate(detections):
            for j in np.nonzero(k == c)[0]:
                records.append((s[j], i, b[j]))
        records.sort(key=lambda r: -r[0])
        used = [np.zeros(int((g[1] == c).sum()), bool) for g in ground_truth]
        tp = np.zeros(len(records))
        for r, (_, i, box) in enumerate(records):
            gt = ground_truth[i][0][ground_truth[i][1] == c]
            if len(gt) == 0:
                continue
            ious = anc.iou(box[None], gt)[0]
            ious[used[i]] = -1
            j = int(ious.argmax())
            if ious[j] >= 0.5:
                used[i][j] = True
                tp[r] = 1
        if not records:
            aps[c] = 0.0
            continue
        ctp = np.cumsum(tp)
        recall = ctp / n_gt
        precision = ctp / np.arange(1, len(records) + 1)
        # All-point interpolation: precision made monotone, integrated over recall steps.
        mrec = np.concatenate([[0.0], recall, [1.0]])
        mpre = np.concatenate([[0.0], precision, [0.0]])
        mpre = np.maximum.accumulate(mpre[::-1])[::-1]
        steps = np.nonzero(mrec[1:] != mrec[:-1])[0]
        aps[c] = float(np.sum((mrec[steps + 1] - mrec[steps]) * mpre[steps + 1]))
    return (float(np.mean(list(aps.values()))) if aps else 0.0), aps


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="AP@0.5 of a trained checkpoint on a COCO data set.")
    ap.add_argument("--checkpoint", type=Path, required=True)
    ap.add_argument("--data", type=Path, required=True, help="folder with coco_instances.json")
    ap.add_argument("--limit", type=int, default=0, help="first N images only")
    args = ap.parse_args(argv)
    model = load_checkpoint(args.checkpoint).eval()
    data = CocoSet(args.data / "coco_instances.json")
    n = min(len(data), args.limit) if args.limit else len(data)
    anchors = anc.generate()
    dets = []
    with torch.no_grad():
        for s in range(0, n, 16):
            idx = range(s, min(s + 16, n))
            boxes, logits = model(data.images_tensor(idx, model.image_size))
            dets += [decode_detections(b.numpy(), l.numpy(), anchors) for b, l in zip(boxes, logits)]
    m, aps = average_precision_50(dets, data.gt[:n], model.detector.num_classes)
    print("AP@0.5 over %d images: %.3f (%d classes with ground truth)" % (n, m, len(aps)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""The 1917 SSD anchors of the TF Object Detection API ssd_mobilenet_v2 300x300 layout, the
sidecar file that carries them to the C++ runtime, and the box coder used for training.

Layout (anchor_generator.ssd_anchor_generator of the TF OD API, as in the shared OIDv4 model):
feature maps 19, 10, 5, 3, 2, 1; scales linear from min_scale 0.2 to max_scale 0.95; aspect ratios
1, 2, 1/2, 3, 1/3 plus one box of scale sqrt(s_i * s_{i+1}) and ratio 1 (s_6 = 1); the lowest layer
is reduced to three boxes (0.1, 1), (s_0, 2), (s_0, 1/2). Anchors are normalised to [0, 1] image
coordinates, centred in their cell, ordered (row, column, anchor) within a layer and layer after
layer: the order of the box predictor outputs after NHWC flattening.

Box coder (FasterRcnnBoxCoder, scale factors 10, 10, 5, 5), in TF order (ty, tx, th, tw):
    ty = 10 (yc - ya) / ha,  tx = 10 (xc - xa) / wa,  th = 5 log(h / ha),  tw = 5 log(w / wa)
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

FEATURE_MAP_SIZES = (19, 10, 5, 3, 2, 1)
MIN_SCALE, MAX_SCALE = 0.2, 0.95
ASPECT_RATIOS = (1.0, 2.0, 0.5, 3.0, 1.0 / 3.0)
SCALE_FACTORS = (10.0, 10.0, 5.0, 5.0)
NUM_ANCHORS = 1917


def box_specs(num_layers: int = len(FEATURE_MAP_SIZES)) -> list:
    """Per layer, the (scale, aspect ratio) of each anchor of a cell, in predictor order."""
    scales = [MIN_SCALE + (MAX_SCALE - MIN_SCALE) * i / (num_layers - 1) for i in range(num_layers)]
    scales.append(1.0)
    specs = []
    for i in range(num_layers):
        if i == 0:
            specs.append([(0.1, 1.0), (scales[0], 2.0), (scales[0], 0.5)])
        else:
            layer = [(scales[i], ar) for ar in ASPECT_RATIOS]
            layer.append((math.sqrt(scales[i] * scales[i + 1]), 1.0))
            specs.append(layer)
    return specs


def anchors_per_cell() -> list:
    return [len(s) for s in box_specs()]


def generate() -> np.ndarray:
    """[1917, 4] float32 anchors (ycenter, xcenter, h, w), normalised."""
    out = []
    for size, specs in zip(FEATURE_MAP_SIZES, box_specs()):
        centres = (np.arange(size, dtype=np.float64) + 0.5) / size
        hw = np.array([(s / math.sqrt(ar), s * math.sqrt(ar)) for s, ar in specs])
        yc, xc, a = np.meshgrid(centres, centres, np.arange(len(specs)), indexing="ij")
        out.append(np.stack([yc.ravel(), xc.ravel(), hw[a.ravel(), 0], hw[a.ravel(), 1]], axis=1))
    anchors = np.concatenate(out).astype(np.float32)
    assert anchors.shape == (NUM_ANCHORS, 4), anchors.shape
    return anchors


def write_sidecar(path, anchors: np.ndarray | None = None) -> None:
    """CSV the C++ post-processing reads (host/detect read_anchor_file): the header line
    'ycenter,xcenter,height,width', then one anchor per line in output-row order, four
    '%.9g' floats (float32 round-trips exactly)."""
    anchors = generate() if anchors is None else anchors
    np.savetxt(path, anchors, fmt="%.9g", delimiter=",", header="ycenter,xcenter,height,width",
               comments="")


def read_sidecar(path) -> np.ndarray:
    lines = Path(path).read_text().splitlines()
    if not lines or lines[0] != "ycenter,xcenter,height,width":
        raise ValueError("%s: first line must be 'ycenter,xcenter,height,width'" % path)
    rows = np.array([[float(v) for v in line.split(",")] for line in lines[1:] if line], np.float32)
    if rows.ndim != 2 or rows.shape[1] != 4:
        raise ValueError("%s: expected lines of 4 numbers, read %s" % (path, rows.shape))
    return rows


def corners(boxes_cwh: np.ndarray) -> np.ndarray:
    """(yc, xc, h, w) -> (ymin, xmin, ymax, xmax)."""
    yc, xc, h, w = np.moveaxis(boxes_cwh, -1, 0)
    return np.stack([yc - h / 2, xc - w / 2, yc + h / 2, xc + w / 2], axis=-1)


def iou(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """IoU matrix [len(a), len(b)] of corner boxes (ymin, xmin, ymax, xmax)."""
    tl = np.maximum(a[:, None, :2], b[None, :, :2])
    br = np.minimum(a[:, None, 2:], b[None, :, 2:])
    inter = np.prod(np.clip(br - tl, 0, None), axis=-1)
    area_a = np.prod(a[:, 2:] - a[:, :2], axis=-1)
    area_b = np.prod(b[:, 2:] - b[:, :2], axis=-1)
    return inter / np.maximum(area_a[:, None] + area_b[None, :] - inter, 1e-12)


def encode(boxes_cwh: np.ndarray, anchors: np.ndarray) -> np.ndarray:
    """Boxes (yc, xc, h, w) against their anchors -> targets (ty, tx, th, tw)."""
    sy, sx, sh, sw = SCALE_FACTORS
    ya, xa, ha, wa = anchors.T
    yc, xc, h, w = boxes_cwh.T
    return np.stack([sy * (yc - ya) / ha, sx * (xc - xa) / wa,
                     sh * np.log(h / ha), sw * np.log(w / wa)], axis=1).astype(np.float32)


def decode(codes: np.ndarray, anchors: np.ndarray) -> np.ndarray:
    """Targets (ty, tx, th, tw) -> boxes (yc, xc, h, w); the inverse of encode."""
    sy, sx, sh, sw = SCALE_FACTORS
    ya, xa, ha, wa = anchors.T
    ty, tx, th, tw = codes.T
    return np.stack([ty / sy * ha + ya, tx / sx * wa + xa,
                     np.exp(th / sh) * ha, np.exp(tw / sw) * wa], axis=1)


def match(gt_corners: np.ndarray, gt_labels: np.ndarray, anchors: np.ndarray,
          threshold: float = 0.5):
    """Assign each anchor a class (0 background) and box targets: an anchor takes the ground-truth
    box it overlaps most if that IoU >= threshold, and every ground-truth box takes its best anchor
    (TF OD API ArgMaxMatcher with force_match_for_each_row). Returns (labels [A] int64,
    targets [A, 4] float32, zero where unmatched)."""
    num = len(anchors)
    labels = np.zeros(num, np.int64)
    targets = np.zeros((num, 4), np.float32)
    if len(gt_corners) == 0:
        return labels, targets
    overlaps = iou(corners(anchors), gt_corners)           # [A, G]
    best_gt = overlaps.argmax(axis=1)
    matched = overlaps[np.arange(num), best_gt] >= threshold
    best_anchor = overlaps.argmax(axis=0)                  # each GT forced to its best anchor
    best_gt[best_anchor] = np.arange(len(gt_corners))
    matched[best_anchor] = True
    idx = np.nonzero(matched)[0]
    g = gt_corners[best_gt[idx]]
    gt_cwh = np.stack([(g[:, 0] + g[:, 2]) / 2, (g[:, 1] + g[:, 3]) / 2,
                       g[:, 2] - g[:, 0], g[:, 3] - g[:, 1]], axis=1)
    labels[idx] = gt_labels[best_gt[idx]]
    targets[idx] = encode(gt_cwh, anchors[idx])
    return labels, targets


def main(argv=None) -> int:
    import argparse
    ap = argparse.ArgumentParser(description="Write the 1917 SSD anchors as the CSV sidecar the C++ post-processing reads.")
    ap.add_argument("output")
    args = ap.parse_args(argv)
    write_sidecar(args.output)
    print("wrote %d anchors to %s" % (NUM_ANCHORS, args.output))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

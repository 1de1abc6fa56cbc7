"""Naming accuracy of a namer against the detector's own class, on bins (docs/detect.md "Naming the parts").

For every part at least --min-visible seen in a bin's passive left view (im0_passive.png, BOP
scene_gt / scene_gt_info), the detector runs on a square tile centred on the part, of side
(part's longer side) / 0.29 (the part's share of a tile in pick's `--tile auto`, clipped to the
image), at score 0.03 as pick does; its classes at the part are those of its boxes overlapping the
part's visible box by IoU >= 0.5, best score first (what pick's proposals pose). The namer runs
(cv2.dnn, as the C++ namer) at the ground-truth box and at the detector's best box there.
Writes a JSON of top-1/3/5 accuracies:

  namer_at_gt        the namer at the ground-truth box, all parts
  detector           the detector's class order, all parts (a part it did not find is a miss)
  namer_at_detection the namer at the detector's best box, all parts (not found: a miss)
  product            namer x (detector score + 0.05) at the detector's best box (pick's --namer-mix product)

    python3 -m detect.naming_eval --bins /work/data/bins_test --namer models/tless-namer/model.onnx --out r.json
"""
from __future__ import annotations

import argparse
import json
from pathlib import Path

import cv2
import numpy as np

from . import anchors as anc
from .detect_eval import decode_detections
from .naming_data import bin_instances, read_labels, square_crop

ROOT = Path(__file__).resolve().parents[2]
TILE_SHARE = 0.29
SCORE = 0.03
UNPROPOSED = 0.05


def namer_probabilities(net, settings: dict, grey: np.ndarray, box_xywh) -> np.ndarray:
    crop = square_crop(grey, box_xywh, settings["input_size"], settings["margin"]).astype(np.float32) / 255.0
    crop = (crop - crop.mean()) / (crop.std() + settings["std_floor"])
    net.setInput(crop[None, None])
    z = net.forward().reshape(-1)
    p = np.exp(z - z.max())
    return p / p.sum()


def detector_at(net, anchors, bgr: np.ndarray, box_xywh, n_classes: int):
    """Detections (corners xyxy in pixels, scores, class indices 0-based) on the part's tile."""
    x, y, w, h = box_xywh
    rows, cols = bgr.shape[:2]
    side = int(min(max(w, h) / TILE_SHARE, rows, cols))
    x0 = int(np.clip(x + w / 2 - side / 2, 0, cols - side))
    y0 = int(np.clip(y + h / 2 - side / 2, 0, rows - side))
    tile = bgr[y0:y0 + side, x0:x0 + side]
    net.setInput(cv2.dnn.blobFromImage(tile, 1.0 / 127.5, (300, 300), (127.5, 127.5, 127.5), swapRB=True))
    enc, logits = net.forward(["box_encodings", "class_logits"])
    b, s, c = decode_detections(enc[0], logits[0], anchors, score_threshold=SCORE)
    xyxy = np.stack([b[:, 1] * side + x0, b[:, 0] * side + y0, b[:, 3] * side + x0, b[:, 2] * side + y0], 1)
    return xyxy, s, c - 1


def iou_xyxy(boxes: np.ndarray, box: np.ndarray) -> np.ndarray:
    tl = np.maximum(boxes[:, :2], box[:2])
    br = np.minimum(boxes[:, 2:], box[2:])
    inter = np.prod(np.clip(br - tl, 0, None), 1)
    area = lambda b: (b[..., 2] - b[..., 0]) * (b[..., 3] - b[..., 1])
    return inter / (area(boxes) + area(box) - inter)


def rank_hit(order, truth: int) -> int:
    """1-based rank of `truth` in `order`, a large number when absent."""
    order = list(order)
    return order.index(truth) + 1 if truth in order else 10 ** 6


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bins", type=Path, required=True)
    p.add_argument("--namer", type=Path, default=ROOT / "models/tless-namer/model.onnx")
    p.add_argument("--detector", type=Path, default=ROOT / "models/tless-ssd/model.onnx")
    p.add_argument("--min-visible", type=float, default=0.5)
    p.add_argument("--out", type=Path, required=True)
    a = p.parse_args()
    ids = read_labels(a.detector.parent / "labels.txt")
    if read_labels(a.namer.parent / "labels.txt") != ids:
        raise SystemExit(f"error: {a.namer.parent / 'labels.txt'}: not the detector's parts")
    class_of = {c: i for i, c in enumerate(ids)}
    settings = json.loads((a.namer.parent / "model.json").read_text())
    namer = cv2.dnn.readNetFromONNX(str(a.namer))
    detector = cv2.dnn.readNetFromONNX(str(a.detector))
    anchors = anc.read_sidecar(a.detector.parent / "anchors.csv")
    ranks = {k: [] for k in ("namer_at_gt", "detector", "namer_at_detection", "product")}
    found = 0
    for image_path, parts in bin_instances(a.bins, a.min_visible):
        bgr = cv2.imread(str(image_path), cv2.IMREAD_COLOR)
        grey = cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY)
        for obj_id, box in parts:
            truth = class_of[obj_id]
            pg = namer_probabilities(namer, settings, grey, box)
            ranks["namer_at_gt"].append(rank_hit(np.argsort(-pg, kind="stable"), truth))
            xyxy, s, c = detector_at(detector, anchors, bgr, box, len(ids))
            gt = np.array([box[0], box[1], box[0] + box[2], box[1] + box[3]], np.float64)
            near = np.nonzero(iou_xyxy(xyxy, gt) >= 0.5)[0] if len(s) else np.zeros(0, int)
            if near.size == 0:
                for k in ("detector", "namer_at_detection", "product"):
                    ranks[k].append(10 ** 6)
                continue
            found += 1
            near = near[np.argsort(-s[near], kind="stable")]
            order = list(dict.fromkeys(int(c[i]) for i in near))
            ranks["detector"].append(rank_hit(order, truth))
            best = xyxy[near[0]]
            pd = namer_probabilities(namer, settings, grey, [best[0], best[1], best[2] - best[0], best[3] - best[1]])
            ranks["namer_at_detection"].append(rank_hit(np.argsort(-pd, kind="stable"), truth))
            det = np.zeros(len(ids))
            for i in near[::-1]:
                det[c[i]] = max(det[c[i]], s[i])
            ranks["product"].append(rank_hit(np.argsort(-(pd * (det + UNPROPOSED)), kind="stable"), truth))
    n = len(ranks["namer_at_gt"])
    report = {"bins": str(a.bins), "parts": n, "detector_found": found}
    for k, r in ranks.items():
        r = np.array(r)
        report[k] = {f"top{t}": float((r <= t).mean()) for t in (1, 3, 5)}
    a.out.write_text(json.dumps(report, indent=1) + "\n")
    print(json.dumps(report, indent=1))


if __name__ == "__main__":
    main()

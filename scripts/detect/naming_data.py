"""Crops of single parts for the naming stage (host/detect/part_namer.h), from our own renders.

A crop is what the namer sees at a detector's box: the square around the box's centre, side
max(w, h) x (1 + 2 margin), pixels outside the image repeated from its edge, grey, resized to
SIZE x SIZE (INTER_AREA). At run time the margin is fixed (NAMING_MARGIN, the C++ namer's); for
training the box is jittered as a detector's box would be: margin, centre and side drawn per crop.

Sources:
  --coco DIR   a `flexsight synth full` folder (coco_instances.json; the boxes are the visible ones)
  --bins DIR   a folder of `flexsight synth bin` bins or MiddEval3+BOP bins (im0_passive.png,
               scene_gt.json obj ids, scene_gt_info.json bbox_visib), parts at least --min-visible seen

    python3 -m detect.naming_data --coco full_train --bins bins500 --jitter 2 --out train.npz
"""
from __future__ import annotations

import argparse
import json
import math
from pathlib import Path

import cv2
import numpy as np

NAMING_MARGIN = 0.15  # each side, fraction of the box's longer side (the C++ namer's)


def read_labels(path: Path) -> list[int]:
    """Category ids in class order from a detector's labels.txt (index 0 the background)."""
    ids = []
    for line in path.read_text().splitlines():
        parts = line.split()
        if len(parts) >= 3 and int(parts[0]) > 0:
            ids.append(int(parts[1]))
    return ids


def square_crop(grey: np.ndarray, box_xywh, size: int, margin: float = NAMING_MARGIN,
                shift=(0.0, 0.0), scale: float = 1.0) -> np.ndarray:
    """The namer's crop of `box_xywh` (pixels); shift in units of the side, scale of the side."""
    x, y, w, h = (float(v) for v in box_xywh)
    side = max(w, h) * (1.0 + 2.0 * margin) * scale
    cx = x + w / 2.0 + shift[0] * side
    cy = y + h / 2.0 + shift[1] * side
    # floor(v + 0.5), as the C++ namer rounds (Python's round() goes to even on halves).
    s = max(4, int(math.floor(side + 0.5)))
    x0 = int(math.floor(cx - s / 2.0 + 0.5))
    y0 = int(math.floor(cy - s / 2.0 + 0.5))
    rows, cols = grey.shape
    ix0, iy0 = max(0, x0), max(0, y0)
    ix1, iy1 = min(cols, x0 + s), min(rows, y0 + s)
    if ix1 <= ix0 or iy1 <= iy0:
        return np.zeros((size, size), np.uint8)
    inside = grey[iy0:iy1, ix0:ix1]
    patch = cv2.copyMakeBorder(inside, iy0 - y0, y0 + s - iy1, ix0 - x0, x0 + s - ix1, cv2.BORDER_REPLICATE)
    return cv2.resize(patch, (size, size), interpolation=cv2.INTER_AREA)


def coco_instances(folder: Path):
    """(image path, [(category_id, box_xywh), ...]) per image of a synth full folder."""
    coco = json.loads((folder / "coco_instances.json").read_text())
    by_image = {}
    for a in coco["annotations"]:
        by_image.setdefault(a["image_id"], []).append((a["category_id"], a["bbox"]))
    for im in coco["images"]:
        yield folder / im["file_name"], by_image.get(im["id"], [])


def bin_instances(folder: Path, min_visible: float):
    """(im0_passive.png, [(obj_id, bbox_visib), ...]) per bin folder under `folder`."""
    for bin_dir in sorted(p for p in folder.iterdir() if (p / "scene_gt_info.json").exists()):
        gt = json.loads((bin_dir / "scene_gt.json").read_text())
        info = json.loads((bin_dir / "scene_gt_info.json").read_text())
        key = sorted(gt.keys())[0]
        parts = [(g["obj_id"], i["bbox_visib"]) for g, i in zip(gt[key], info[key])
                 if i["visib_fract"] >= min_visible and i["bbox_visib"][2] > 0 and i["bbox_visib"][3] > 0]
        yield bin_dir / "im0_passive.png", parts


def crops_of(instances, class_of: dict, size: int, jitter: int, rng: np.random.Generator):
    """Crops and class indices; jitter 0: one crop per part at the run-time margin."""
    xs, ys, boxes = [], [], []
    for image_path, parts in instances:
        if not parts:
            continue
        grey = cv2.imread(str(image_path), cv2.IMREAD_GRAYSCALE)
        if grey is None:
            raise SystemExit(f"error: {image_path}: cannot read the image")
        for category_id, box in parts:
            if category_id not in class_of:
                continue
            for _ in range(max(1, jitter)):
                if jitter == 0:
                    crop = square_crop(grey, box, size)
                else:
                    # A detector's box: edges off by about a tenth of the part, margins vary.
                    crop = square_crop(grey, box, size, margin=rng.uniform(0.0, 0.3),
                                       shift=rng.normal(0.0, 0.05, 2), scale=float(np.exp(rng.normal(0.0, 0.1))))
                xs.append(crop)
                ys.append(class_of[category_id])
                boxes.append(max(box[2], box[3]))
    return np.array(xs, np.uint8).reshape(-1, size, size), np.array(ys, np.int64), np.array(boxes, np.float32)


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--coco", type=Path, action="append", default=[])
    p.add_argument("--bins", type=Path, action="append", default=[])
    p.add_argument("--labels", type=Path, default=Path(__file__).resolve().parents[2] / "models/tless-ssd/labels.txt")
    p.add_argument("--size", type=int, default=64)
    p.add_argument("--jitter", type=int, default=0, help="jittered crops per part (0: one at the run-time margin)")
    p.add_argument("--min-visible", type=float, default=0.5)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--out", type=Path, required=True)
    a = p.parse_args()
    ids = read_labels(a.labels)
    class_of = {c: i for i, c in enumerate(ids)}
    rng = np.random.default_rng(a.seed)
    xs, ys, sizes, sources = [], [], [], []
    for folder in a.coco:
        x, y, s = crops_of(coco_instances(folder), class_of, a.size, a.jitter, rng)
        xs.append(x), ys.append(y), sizes.append(s), sources.append(np.zeros(len(y), np.int8))
    for folder in a.bins:
        x, y, s = crops_of(bin_instances(folder, a.min_visible), class_of, a.size, a.jitter, rng)
        xs.append(x), ys.append(y), sizes.append(s), sources.append(np.ones(len(y), np.int8))
    np.savez_compressed(a.out, x=np.concatenate(xs), y=np.concatenate(ys), box_px=np.concatenate(sizes),
                        bin=np.concatenate(sources), category_ids=np.array(ids, np.int64))
    print(f"{a.out}: {sum(len(y) for y in ys)} crops of {a.size}x{a.size} "
          f"({', '.join(str(len(y)) for y in ys)} per source)")


if __name__ == "__main__":
    main()

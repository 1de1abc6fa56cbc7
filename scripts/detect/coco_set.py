"""A COCO-instances data set (as `flexsight synth` writes it) for training and evaluation: the
images in id order, their boxes normalised to corners (ymin, xmin, ymax, xmax), classes 1..C in
the order of the sorted category ids, and the images as network inputs in [-1, 1]."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import torch
from PIL import Image


def normalised(boxes, w: float, h: float) -> np.ndarray:
    """[x, y, w, h] pixel boxes -> [N, 4] corners (ymin, xmin, ymax, xmax) over the image size."""
    return np.array([[y / h, x / w, (y + bh) / h, (x + bw) / w] for x, y, bw, bh in boxes],
                    np.float32).reshape(-1, 4)


class CocoSet:
    """Images and boxes of a COCO instances file; boxes normalised, class 1..C by sorted id."""

    def __init__(self, coco_path: Path, limit: int = 0):
        coco = json.loads(coco_path.read_text())
        self.root = coco_path.parent
        self.categories = sorted(coco["categories"], key=lambda c: c["id"])
        index = {c["id"]: i + 1 for i, c in enumerate(self.categories)}
        self.images = sorted(coco["images"], key=lambda im: im["id"])
        if limit:  # the first images of a data set: the data-size experiments share one set
            self.images = self.images[:limit]
            kept = {im["id"] for im in self.images}
            coco["annotations"] = [a for a in coco["annotations"] if a["image_id"] in kept]
        boxes = {im["id"]: [] for im in self.images}
        crowds = {im["id"]: [] for im in self.images}
        for a in coco["annotations"]:
            if a["bbox"][2] <= 0 or a["bbox"][3] <= 0:
                continue
            if a.get("iscrowd", 0):
                crowds[a["image_id"]].append(a["bbox"])
            else:
                boxes[a["image_id"]].append((a["bbox"], index[a["category_id"]]))
        self.gt, self.crowds = [], []  # crowd regions: neither part nor background (detect.train)
        for im in self.images:
            w, h = float(im["width"]), float(im["height"])
            c = normalised([b for b, _ in boxes[im["id"]]], w, h)
            l = np.array([k for _, k in boxes[im["id"]]], np.int64)
            self.gt.append((c, l))
            self.crowds.append(normalised(crowds[im["id"]], w, h))
        self.sources = [im.get("source", "") for im in self.images]

    def __len__(self):
        return len(self.images)

    def path(self, i: int) -> Path:
        return self.root / self.images[i]["file_name"]

    def image_tensor(self, i: int, size: int) -> torch.Tensor:
        img = Image.open(self.path(i)).convert("RGB")
        if img.size != (size, size):
            img = img.resize((size, size), Image.BILINEAR)
        x = np.asarray(img, np.float32) / 127.5 - 1.0
        return torch.from_numpy(x.transpose(2, 0, 1).copy())

    def images_tensor(self, idx, size: int) -> torch.Tensor:
        return torch.stack([self.image_tensor(int(i), size) for i in idx])

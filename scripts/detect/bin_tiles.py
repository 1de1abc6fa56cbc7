"""Detection training data from `flexsight synth bin` bins: the passive left view (what pick
detects on) whole and cut into the tiles pick and eval-det cut, as one COCO-instances folder
that detect.train reads like a `flexsight synth full` folder.

    python3 -m detect.bin_tiles BINS... -o OUT [--tile 256 336] [--min-visible 0.5]
                                [--shifts 0] [--seed 1] [--no-whole]      # from scripts/

BINS are bin folders (rgb/000000.png, scene_gt.json, scene_gt_info.json, mask_visib/) or
folders of them (a `synth bin -o` folder). Tiles follow host/detect/tiled_detection.cpp's
fixed_tiling: squares of N px, starts spread evenly at most 3/4 N apart, the last row and
column at the image's edge. A part's box in a tile is the box of its visible mask pixels
inside the tile; its share is those pixels over the part's whole (unoccluded) pixel count,
the measure eval-det's --min-visible applies to visib_fract. Parts with a share of at least
--min-visible are boxes; those with less but some pixels in the image are written as crowd
regions (iscrowd 1), as eval-det treats them: detect.train leaves them out of the targets.
--shifts K adds K more grids per bin and tile size, shifted by a seeded random offset
below the stride, so that parts fall at other places of a tile (the seed fixes them).
"""
from __future__ import annotations

import argparse
import json
import random
import sys
from pathlib import Path

import numpy as np
from PIL import Image

DEFAULT_LABELS = Path(__file__).resolve().parents[2] / "models" / "tless-ssd" / "labels.txt"


def tile_starts(length: int, tile: int, stride: int) -> list[int]:
    """host/detect/tiled_detection.cpp's tile_starts: evenly spread, first 0, last length-tile."""
    if tile >= length:
        return [0]
    span = length - tile
    gaps = (span + stride - 1) // stride
    return [int(np.floor(i * span / gaps + 0.5)) for i in range(gaps + 1)]


def grid(width: int, height: int, tile: int, shift: tuple[int, int] = (0, 0)):
    """Tiles (x, y, w, h) of fixed_tiling(tile) over the image; a shift moves every start but
    the first and the last, so that the grid still covers the image."""
    stride = max(1, tile * 3 // 4)
    xs, ys = tile_starts(width, tile, stride), tile_starts(height, tile, stride)
    if shift != (0, 0):
        xs = [0] + [min(x + shift[0], width - tile) for x in xs[1:-1]] + xs[-1:] if len(xs) > 1 else xs
        ys = [0] + [min(y + shift[1], height - tile) for y in ys[1:-1]] + ys[-1:] if len(ys) > 1 else ys
        xs, ys = sorted(set(xs)), sorted(set(ys))
    return [(x, y, min(tile, width - x), min(tile, height - y)) for y in ys for x in xs]


def read_labels(path: Path) -> list[dict]:
    """The detector's categories from its labels.txt (`INDEX CATEGORY_ID NAME`, 0 background)."""
    cats = []
    for line in path.read_text().splitlines():
        index, cat_id, name = line.split()[:3]
        if int(index) > 0:
            cats.append({"id": int(cat_id), "name": name, "supercategory": "tless"})
    return cats


def find_bins(paths: list[Path]) -> list[Path]:
    bins = []
    for p in paths:
        if (p / "scene_gt.json").is_file():
            bins.append(p)
        elif p.is_dir() and any(c.is_dir() and (c / "scene_gt.json").is_file() for c in p.iterdir()):
            bins += sorted(c for c in p.iterdir() if (c / "scene_gt.json").is_file())
        else:
            raise ValueError("%s: not a synth bin folder (no scene_gt.json in it or its folders)" % p)
    return bins


class Bin:
    """One bin's passive left view and, per part, its category, whole pixel count and visible mask."""

    def __init__(self, folder: Path, category_ids: set[int]):
        self.folder = folder
        gt = json.loads((folder / "scene_gt.json").read_text())
        info = json.loads((folder / "scene_gt_info.json").read_text())
        key = sorted(gt, key=int)[0]
        self.image_path = folder / "rgb" / ("%06d.png" % int(key))
        if not self.image_path.is_file():
            raise ValueError("%s: missing" % self.image_path)
        self.parts = []
        for k, (g, i) in enumerate(zip(gt[key], info[key])):
            if g["obj_id"] not in category_ids:
                raise ValueError("%s: part %d is obj_id %d, not a category of the detector"
                                 % (folder / "scene_gt.json", k, g["obj_id"]))
            if i["px_count_visib"] <= 0:
                continue
            mask_path = folder / "mask_visib" / ("%06d_%06d.png" % (int(key), k))
            if not mask_path.is_file():
                raise ValueError("%s: missing (synth bin writes the visible masks)" % mask_path)
            self.parts.append((g["obj_id"], max(1, i["px_count_all"]), mask_path))
        self._masks = None

    def masks(self):
        if self._masks is None:
            self._masks = [np.asarray(Image.open(p)) > 0 for _, _, p in self.parts]
        return self._masks

    def annotations(self, rect):
        """(category, [x, y, w, h] in the rect, share of the whole part inside) per part
        with visible pixels in rect = (x, y, w, h)."""
        x0, y0, w, h = rect
        out = []
        for (cat, px_all, _), mask in zip(self.parts, self.masks()):
            m = mask[y0:y0 + h, x0:x0 + w]
            px = int(m.sum())
            if px == 0:
                continue
            rows, cols = np.flatnonzero(m.any(1)), np.flatnonzero(m.any(0))
            box = [int(cols[0]), int(rows[0]), int(cols[-1] - cols[0] + 1), int(rows[-1] - rows[0] + 1)]
            out.append((cat, box, round(px / px_all, 4)))
        return out


def build(args) -> dict:
    cats = read_labels(args.labels)
    bins = [Bin(b, {c["id"] for c in cats}) for b in find_bins(args.bins)]
    for b in bins:  # every problem before anything is written
        with Image.open(b.image_path) as im:
            w, h = im.size
        for tile in args.tile:
            if tile > min(w, h):
                raise ValueError("--tile %d: larger than %s (%dx%d)" % (tile, b.image_path, w, h))
    rng = random.Random(args.seed)
    images, annotations = [], []
    (args.out / "images").mkdir(parents=True)

    def add(image: Image.Image, name: str, bin_: Bin, rect):
        image_id = len(images)
        image.save(args.out / "images" / name)
        images.append({"id": image_id, "file_name": "images/" + name, "width": rect[2],
                       "height": rect[3], "bin": str(bin_.folder), "rect": list(rect)})
        for cat, box, share in bin_.annotations(rect):
            crowd = int(share < args.min_visible)
            annotations.append({"id": len(annotations), "image_id": image_id, "category_id": cat,
                                "bbox": box, "area": box[2] * box[3], "iscrowd": crowd,
                                "visib_fract": share})

    for n, b in enumerate(bins):
        view = Image.open(b.image_path).convert("RGB")
        w, h = view.size
        if not args.no_whole:
            add(view, "bin%03d_whole.png" % n, b, (0, 0, w, h))
        for tile in args.tile:
            stride = max(1, tile * 3 // 4)
            shifts = [(0, 0)] + [(rng.randrange(1, stride), rng.randrange(1, stride))
                                 for _ in range(args.shifts)]
            for s, shift in enumerate(shifts):
                for t, rect in enumerate(grid(w, h, tile, shift)):
                    x, y, tw, th = rect
                    add(view.crop((x, y, x + tw, y + th)), "bin%03d_t%d_s%d_%02d.png" % (n, tile, s, t),
                        b, rect)
        b._masks = None  # one bin's masks in memory at a time
    return {"info": {"description": "flexsight bin_tiles", "bins": len(bins), "tile": args.tile,
                     "shifts": args.shifts, "seed": args.seed, "min_visible": args.min_visible},
            "images": images, "annotations": annotations, "categories": cats}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("bins", type=Path, nargs="+", help="synth bin folders (or folders of them)")
    ap.add_argument("-o", "--out", type=Path, required=True, help="the COCO folder to make (must not exist)")
    ap.add_argument("--tile", type=int, nargs="+", default=[256],
                    help="tile sizes in pixels (default 256, eval-det's and detect's on 1280x960 bins)")
    ap.add_argument("--min-visible", type=float, default=0.5,
                    help="parts with less of them in the image or tile are crowd regions (default 0.5)")
    ap.add_argument("--shifts", type=int, default=0, help="extra shifted grids per bin and tile size")
    ap.add_argument("--seed", type=int, default=1, help="seed of the shifts")
    ap.add_argument("--no-whole", action="store_true", help="tiles only, not the whole view")
    ap.add_argument("--labels", type=Path, default=DEFAULT_LABELS,
                    help="the detector's labels.txt: the categories (default the shipped model's)")
    args = ap.parse_args(argv)
    problems = []
    if args.out.exists():
        problems.append("-o %s: exists already" % args.out)
    if any(t < 64 for t in args.tile):
        problems.append("--tile: at least 64 pixels")
    if not 0.0 <= args.min_visible <= 1.0:
        problems.append("--min-visible %g: not in [0, 1]" % args.min_visible)
    if args.shifts < 0:
        problems.append("--shifts %d: negative" % args.shifts)
    if not args.labels.is_file():
        problems.append("--labels %s: missing" % args.labels)
    if problems:
        print("error: " + problems[0], file=sys.stderr)
        return 1
    try:
        coco = build(args)
    except ValueError as e:
        print("error: %s" % e, file=sys.stderr)
        return 1
    (args.out / "coco_instances.json").write_text(json.dumps(coco, indent=1) + "\n")
    boxes = sum(1 for a in coco["annotations"] if not a["iscrowd"])
    print("bin_tiles: %d bins -> %d images (%d boxes, %d crowd regions) in %s"
          % (coco["info"]["bins"], len(coco["images"]), boxes, len(coco["annotations"]) - boxes,
             args.out))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

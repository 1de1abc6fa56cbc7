#!/usr/bin/python3
"""Bad-2 and average error of disparity results on the projector-lit bins, split into
all / non-occluded / parts / floor / walls pixels (docs/stereo.md, "Projector-lit bins").

usage: scripts/stereo/bins_figures.py SCENE_DIR DISP.pfm [DISP.pfm ...]
       scripts/stereo/bins_figures.py --eval DATASET_ROOT EVAL_OUT [--scenes a,b]
         (EVAL_OUT: a `flexsight eval --out` folder holding <scene>_disp.pfm)
       --mask-png FILE writes the pixel classes of the (first) scene as a PNG.

Pixel classes, all among the pixels with finite ground truth (inf = no surface):
  all    every such pixel (MiddEval3's "all");
  nocc   mask0nocc.png == 255;
  floor  within 1 px of a plane fitted to the ground-truth disparities of the bin floor
         (iterated least squares, started from the lowest 30 % of the disparities: the
         floor is the farthest and the largest surface);
  parts  more than 2 px above that plane (about 4 mm at 1250 mm with f B = 790588 px mm)
         and inside the bounding box of the floor's pixels, shrunk by 4 px: the bin walls
         rise above the floor too but lie outside it in the image;
  walls  the rest of the pixels above the floor.
A scene written by `flexsight synth bin` has BOP masks (mask_visib/*.png, one a part):
there the parts are exactly the pixels of those masks, and floor and walls are the rest
by the rule above (the fitted "floor" is then the table, the "walls" the bin). Either way
"parts nocc" and "parts occ" split the parts by mask0nocc.png: "parts occ" is the parts'
surface that the right camera does not see (a side that faces away from it, or a part
hidden there behind a taller one), which no two-view matcher measures.
A result pixel that is not finite counts as bad (the MiddEval3 SDK convention).
"""
import argparse
import glob
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pfm_io import read_pfm  # noqa: E402


def pixel_classes(scene):
    gt = read_pfm(os.path.join(scene, "disp0GT.pfm"))
    finite = np.isfinite(gt)
    nocc_path = os.path.join(scene, "mask0nocc.png")
    if os.path.exists(nocc_path):
        import cv2
        nocc = (cv2.imread(nocc_path, cv2.IMREAD_GRAYSCALE) == 255) & finite
    else:
        nocc = finite.copy()
    h, w = gt.shape
    ys, xs = np.mgrid[0:h, 0:w]
    values = gt[finite]
    sel = finite & (gt <= np.percentile(values, 30))
    for _ in range(5):
        a = np.stack([xs[sel], ys[sel], np.ones(sel.sum())], axis=1)
        coef, *_ = np.linalg.lstsq(a, gt[sel].astype(np.float64), rcond=None)
        plane = coef[0] * xs + coef[1] * ys + coef[2]
        sel = finite & (np.abs(gt - plane) <= 1.0)
    floor = sel
    above = finite & (gt > plane + 2.0)
    fy, fx = np.where(floor)
    inside = np.zeros_like(finite)
    inside[fy.min() + 4:fy.max() - 3, fx.min() + 4:fx.max() - 3] = True
    parts = above & inside
    walls = above & ~inside
    masks = sorted(glob.glob(os.path.join(scene, "mask_visib", "*.png")))
    if masks:
        import cv2
        parts = np.zeros_like(finite)
        for m in masks:
            parts |= cv2.imread(m, cv2.IMREAD_GRAYSCALE) > 0
        parts &= finite
        floor &= ~parts
        walls = above & ~parts
    return gt, {"all": finite, "nocc": nocc, "parts": parts, "floor": floor, "walls": walls,
                "parts nocc": parts & nocc, "parts occ": parts & ~nocc}


def figures(gt, disp, classes, names=("all", "nocc", "parts", "floor")):
    with np.errstate(invalid="ignore"):
        err = np.abs(disp - gt)
    err[~np.isfinite(disp)] = np.inf
    out = {}
    for name in names:
        m = classes[name]
        e = err[m]
        n = max(int(m.sum()), 1)
        bad = float((e > 2.0).sum()) / n * 100.0
        finite_e = np.where(np.isfinite(e), e, 0.0)
        # Average error over the pixels with a finite result (density below says how many).
        avg = float(finite_e[np.isfinite(e)].mean()) if np.isfinite(e).any() else float("nan")
        out[name] = (bad, avg, int(m.sum()))
    return out


def main():
    p = argparse.ArgumentParser()
    p.add_argument("scene_or_root")
    p.add_argument("results", nargs="+")
    p.add_argument("--eval", action="store_true", help="DATASET_ROOT EVAL_OUT form")
    p.add_argument("--scenes", default=None)
    p.add_argument("--mask-png", default=None)
    args = p.parse_args()
    rows = []
    if args.eval:
        root, out = args.scene_or_root, args.results[0]
        scenes = args.scenes.split(",") if args.scenes else sorted(
            d for d in os.listdir(root) if os.path.isfile(os.path.join(root, d, "disp0GT.pfm")))
        for s in scenes:
            rows.append((s, os.path.join(root, s), os.path.join(out, s + "_disp.pfm")))
    else:
        for r in args.results:
            rows.append((os.path.basename(r), args.scene_or_root, r))
    names = ("all", "nocc", "parts", "parts nocc", "parts occ", "floor", "walls")
    print("| result | " + " | ".join(f"{n} bad-2 | {n} avg" for n in names) + " |")
    print("|---|" + "---:|" * (2 * len(names)))
    sums = {n: [0.0, 0.0, 0] for n in names}
    cache = {}
    for label, scene, result in rows:
        if scene not in cache:
            cache[scene] = pixel_classes(scene)
        gt, classes = cache[scene]
        if args.mask_png and len(cache) == 1:
            import cv2
            img = np.zeros(gt.shape, np.uint8)
            img[classes["floor"]] = 80
            img[classes["walls"]] = 160
            img[classes["parts"]] = 255
            cv2.imwrite(args.mask_png, img)
        f = figures(gt, read_pfm(result), classes, names)
        print(f"| {label} | " + " | ".join(f"{f[n][0]:.2f} | {f[n][1]:.2f}" for n in names) + " |")
        for n in names:
            sums[n][0] += f[n][0]
            sums[n][1] += f[n][1]
            sums[n][2] += 1
    if len(rows) > 1:
        print("| mean | " + " | ".join(
            f"{sums[n][0] / sums[n][2]:.2f} | {sums[n][1] / sums[n][2]:.2f}" for n in names) + " |")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""bad-2 of a disparity inside and outside the projector's field, on `synth bin` scenes.

usage: scripts/stereo/projector_field_split.py SCENE DISP.pfm [SCENE DISP.pfm ...]

The projector's 35-degree field does not reach the sides of the cameras' views at the
table's depth: there the table is lit by the room only and is as texture-less as the
passive images. Which pixels the projector reaches is read off the images, not the
renderer: where im0.png and im0_passive.png differ by more than 12 grey levels in some
channel (a dot), closed with a square of 31 px at 1152 px width (the dots' spacing there,
scaled with the width), so that the gaps between dots count as lit.
Prints, per scene and as the mean over scenes: bad-2 over all pixels with ground truth,
the share of those in the projector's field, bad-2 there, bad-2 outside, and the points
of the total that the outside adds.
"""
import os
import sys

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pfm_io import read_pfm  # noqa: E402

DOT_LEVEL = 12
CLOSING_AT_1152 = 31


def projector_field(scene):
    active = cv2.imread(os.path.join(scene, "im0.png")).astype(np.int16)
    passive = cv2.imread(os.path.join(scene, "im0_passive.png")).astype(np.int16)
    dots = (np.abs(active - passive).max(axis=2) > DOT_LEVEL).astype(np.uint8)
    size = int(round(CLOSING_AT_1152 * dots.shape[1] / 1152)) | 1
    return cv2.morphologyEx(dots, cv2.MORPH_CLOSE, np.ones((size, size), np.uint8)).astype(bool)


def split(scene, disp_path):
    gt = read_pfm(os.path.join(scene, "disp0GT.pfm"))
    disp = read_pfm(disp_path)
    if disp.shape != gt.shape:
        sys.exit(f"projector_field_split: {disp_path} is {disp.shape}, the ground truth {gt.shape}")
    lit = projector_field(scene)
    truth = np.isfinite(gt)
    with np.errstate(invalid="ignore"):
        bad = truth & ~(np.abs(disp - gt) <= 2.0)
    n = truth.sum()
    return {
        "all": bad.sum() / n * 100,
        "field_share": (truth & lit).sum() / n * 100,
        "in_field": bad[truth & lit].mean() * 100,
        "outside": bad[truth & ~lit].mean() * 100 if (truth & ~lit).any() else float("nan"),
        "outside_adds": (bad & ~lit).sum() / n * 100,
    }


def main():
    args = sys.argv[1:]
    if not args or len(args) % 2:
        sys.exit(__doc__)
    rows = []
    print("| scene | bad-2 all | in the projector's field (share of pixels) | bad-2 there | bad-2 outside | points the outside adds |")
    print("|---|---:|---:|---:|---:|---:|")
    for scene, disp in zip(args[0::2], args[1::2]):
        for path in (os.path.join(scene, "im0_passive.png"), os.path.join(scene, "disp0GT.pfm"), disp):
            if not os.path.isfile(path):
                sys.exit(f"projector_field_split: {path}: no such file")
        r = split(scene, disp)
        rows.append(r)
        print(f"| {os.path.join(*os.path.normpath(scene).split(os.sep)[-2:])} | {r['all']:.2f} | {r['field_share']:.1f} % | "
              f"{r['in_field']:.2f} | {r['outside']:.2f} | {r['outside_adds']:.2f} |")
    mean = {k: float(np.mean([r[k] for r in rows])) for k in rows[0]}
    print(f"| mean | {mean['all']:.2f} | {mean['field_share']:.1f} % | {mean['in_field']:.2f} | "
          f"{mean['outside']:.2f} | {mean['outside_adds']:.2f} |")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Photo-consistency of the ground truth of `flexsight synth bin` folders.

For every bin folder under the given roots: the left image warped into the right view
by disp0GT (linear interpolation along the row) against the right image, on the pixels
of mask0nocc, for the passive pair (room light) and the active pair (with the dots).
Prints the share of pixels whose grey levels agree within 2 and within 4 levels and the
median absolute difference. Reads PNG and PFM with NumPy and PIL only.

usage: scripts/sim/check_bin_gt.py BINS_ROOT [BINS_ROOT ...]
"""
import pathlib
import sys

import numpy as np
from PIL import Image


def read_pfm(path):
    with open(path, "rb") as f:
        header = f.readline().strip()
        assert header == b"Pf", header
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.fromfile(f, "<f4" if scale < 0 else ">f4").reshape(height, width)
    return data[::-1]


def grey(path):
    return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64).mean(axis=2)


def consistency(folder, suffix):
    left = grey(folder / f"im0{suffix}.png")
    right = grey(folder / f"im1{suffix}.png")
    disparity = read_pfm(folder / "disp0GT.pfm")
    nocc = np.asarray(Image.open(folder / "mask0nocc.png")) > 0
    ys, xs = np.nonzero(nocc & np.isfinite(disparity))
    u = xs - disparity[ys, xs]
    u0 = np.floor(u).astype(int)
    keep = (u0 >= 0) & (u0 + 1 < right.shape[1])
    ys, xs, u, u0 = ys[keep], xs[keep], u[keep], u0[keep]
    w = u - u0
    warped = (1 - w) * right[ys, u0] + w * right[ys, u0 + 1]
    diff = np.abs(warped - left[ys, xs])
    return len(diff), (diff <= 2).mean(), (diff <= 4).mean(), np.median(diff)


def main():
    folders = []
    for root in map(pathlib.Path, sys.argv[1:]):
        folders += sorted(p.parent for p in root.glob("**/disp0GT.pfm"))
    if not folders:
        sys.exit("no bin folder (with disp0GT.pfm) under " + " ".join(sys.argv[1:]))
    print(f"{'bin':40s} {'pair':8s} {'pixels':>9s} {'<=2':>7s} {'<=4':>7s} {'median':>7s}")
    for folder in folders:
        for suffix, name in (("_passive", "passive"), ("", "active")):
            n, within2, within4, median = consistency(folder, suffix)
            print(f"{str(folder)[-40:]:40s} {name:8s} {n:9d} {within2:7.3f} {within4:7.3f} {median:7.2f}")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Writes the calibration of python3-skimage's Motorcycle pair as a Middlebury calib.txt.

skimage states it in the docstring of skimage.data.stereo_motorcycle (focal length,
principal point, principal point dx, baseline), valid for its 741x500 images. Reading it
from there keeps the numbers coming from the Debian package rather than from us.

usage: skimage_motorcycle_calib.py OUT_CALIB.txt
"""
import re
import sys

import skimage.data


def value(doc, label):
    match = re.search(re.escape(label) + r":\s*([-0-9.]+)", doc)
    if not match:
        sys.exit(f"skimage.data.stereo_motorcycle docstring: no '{label}' (skimage changed?)")
    return float(match.group(1))


def main():
    doc = skimage.data.stereo_motorcycle.__doc__ or ""
    f = value(doc, "Focal length")
    cx = value(doc, "Principal point x")
    cy = value(doc, "Principal point y")
    doffs = value(doc, "Principal point dx")
    baseline = value(doc, "Baseline")
    with open(sys.argv[1], "w") as out:
        out.write(f"cam0=[{f} 0 {cx}; 0 {f} {cy}; 0 0 1]\n"
                  f"cam1=[{f} 0 {cx + doffs:.3f}; 0 {f} {cy}; 0 0 1]\n"
                  f"doffs={doffs}\nbaseline={baseline}\nwidth=741\nheight=500\nndisp=70\n")


if __name__ == "__main__":
    main()

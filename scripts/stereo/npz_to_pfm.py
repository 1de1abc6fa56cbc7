#!/usr/bin/python3
"""Converts the first array of a NumPy .npz archive (a disparity map) to a PFM file.

usage: npz_to_pfm.py IN.npz OUT.pfm   (written atomically: OUT.pfm.tmp, then renamed)
"""
import os
import sys

import numpy as np


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    source, target = sys.argv[1:]
    try:
        archive = np.load(source)
        disparity = archive[archive.files[0]].astype("<f4")
    except Exception as error:  # any unreadable archive: name the file and stop
        raise SystemExit(f"{source}: cannot be read as a NumPy archive ({error})")
    if disparity.ndim != 2:
        raise SystemExit(f"{source}: expected a 2-D disparity array, got shape {disparity.shape}")
    height, width = disparity.shape
    temporary = target + ".tmp"
    with open(temporary, "wb") as f:
        f.write(b"Pf\n%d %d\n-1\n" % (width, height))
        f.write(np.flipud(disparity).tobytes())
    os.replace(temporary, target)


if __name__ == "__main__":
    main()

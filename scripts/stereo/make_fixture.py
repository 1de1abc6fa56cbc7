#!/usr/bin/python3
"""Builds the small real-data test fixture committed under tests/data/.

Takes one Middlebury 2014 quarter-resolution training scene from the shared datasets
folder, halves it (images by 2x2 area averaging, ground truth and mask by taking the
top-left pixel of each 2x2 block, disparities halved) and writes it as a MiddEval3 scene
folder: im0.png, im1.png, disp0GT.pfm, mask0nocc.png, calib.txt (ndisp halved).

usage: scripts/stereo/make_fixture.py DATASETS_ROOT SCENE OUT_DIR
  e.g. scripts/stereo/make_fixture.py ../shared/datasets Teddy tests/data/TeddyH
"""
import os
import sys

import numpy as np
from PIL import Image

from pfm_io import read_pfm, write_pfm


def halve_image(path):
    image = np.asarray(Image.open(path).convert("RGB"), dtype=np.float32)
    h, w = image.shape[0] // 2 * 2, image.shape[1] // 2 * 2
    blocks = image[:h, :w].reshape(h // 2, 2, w // 2, 2, 3).mean(axis=(1, 3))
    return Image.fromarray(np.round(blocks).astype(np.uint8))


def main():
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    root, scene, out = sys.argv[1:]
    source = os.path.join(root, "MiddEval3-trainingQ", scene)
    os.makedirs(out, exist_ok=True)
    halve_image(os.path.join(source, "im0.png")).save(os.path.join(out, "im0.png"), optimize=True)
    halve_image(os.path.join(source, "im1.png")).save(os.path.join(out, "im1.png"), optimize=True)
    gt = read_pfm(os.path.join(source, "disp0GT.pfm"), expect_channels=1)
    h, w = gt.shape[0] // 2 * 2, gt.shape[1] // 2 * 2
    write_pfm(os.path.join(out, "disp0GT.pfm"), gt[:h:2, :w:2] / 2.0)
    mask = np.asarray(Image.open(os.path.join(source, "mask0nocc.png")))
    Image.fromarray(mask[:h:2, :w:2]).save(os.path.join(out, "mask0nocc.png"), optimize=True)
    calib = {}
    for line in open(os.path.join(source, "calib.txt")):
        if "=" in line:
            key, value = line.strip().split("=", 1)
            calib[key] = value
    ndisp = (int(calib["ndisp"]) + 1) // 2
    with open(os.path.join(out, "calib.txt"), "w") as f:
        for key in ("cam0", "cam1"):
            m = [float(v) for v in calib[key].strip("[]").replace(";", " ").split()]
            m[0] /= 2; m[2] /= 2; m[4] /= 2; m[5] /= 2
            f.write(f"{key}=[{m[0]:g} 0 {m[2]:g}; 0 {m[4]:g} {m[5]:g}; 0 0 1]\n")
        f.write(f"doffs={float(calib['doffs']) / 2:g}\nbaseline={calib['baseline']}\n")
        f.write(f"width={w // 2}\nheight={h // 2}\nndisp={ndisp}\n")
    print(f"wrote {out}: {w // 2}x{h // 2}, ndisp {ndisp}")


if __name__ == "__main__":
    main()

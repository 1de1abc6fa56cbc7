#!/usr/bin/python3
"""Bad-2 by region of a stereo result and of the same result after `flexsight projector
decode`, side by side (docs/projector.md, "Measured").

usage: scripts/projector/decode_report.py SCENE... --stereo DIR --decoded DIR
           [--flags DIR] [--label TEXT] [--image FILE.png] [--json FILE]

Each SCENE is a MiddEval3 folder with disp0GT.pfm; DIR/<scene>_disp.pfm is the stereo
result (flexsight stereo -o) and DIR2/<scene>_dec.pfm the decoded one, with
DIR2/<scene>_state.png (decode --state: 255 decoded, 128 refused, 64 invalidated by the
check) when present. The regions are region_report.py's (the same rules, imported), and
bad-2 counts a non-finite result as bad. Prints one Markdown table over all scenes
pooled: per region the pixels, stereo bad-2, decoded bad-2, and how many pixels decode
changed (and the bad-2 of those before and after). --flags DIR reads
DIR/<scene>_check.png (`projector check --mask`) and adds a table of how well the flag
finds the stereo's bad-2 pixels: per region the pixels flagged, precision (flagged
pixels that are bad-2) and recall (bad-2 pixels with a finite stereo value that are
flagged), and the bad-2 share of the finite stereo values before and after dropping the
flagged ones. --image writes per scene a row
(left view, stereo error, decoded error, coloured by region as region_report.py does).
"""
import argparse
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "stereo"))
from pfm_io import read_pfm  # noqa: E402
from region_report import BAD, REGIONS, error_by_region, regions  # noqa: E402

ROWS = ("all",) + REGIONS


def fail(message):
    print(f"decode_report: {message}", file=sys.stderr)
    sys.exit(1)


def bad_of(disp, gt):
    with np.errstate(invalid="ignore"):
        return ~(np.abs(disp - gt) <= BAD)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--stereo", required=True)
    ap.add_argument("--decoded", required=True)
    ap.add_argument("--flags")
    ap.add_argument("--label", default="")
    ap.add_argument("--image")
    ap.add_argument("--json")
    a = ap.parse_args()
    totals = {r: np.zeros(5, np.int64) for r in ROWS}  # n, bad stereo, bad decoded, changed, changed bad before
    changed_bad_after = {r: 0 for r in ROWS}
    # flagged, flagged and bad, bad with a finite stereo value, finite stereo values
    flag_totals = {r: np.zeros(4, np.int64) for r in ROWS}
    rows = []
    for scene in a.scenes:
        name = os.path.basename(os.path.normpath(scene))
        paths = [os.path.join(a.stereo, name + "_disp.pfm"), os.path.join(a.decoded, name + "_dec.pfm")]
        for p in paths:
            if not os.path.isfile(p):
                fail(f"{p} is missing")
        gt, masks = regions(scene)
        stereo, decoded = (read_pfm(p) for p in paths)
        if stereo.shape != gt.shape or decoded.shape != gt.shape:
            fail(f"{scene}: a result is not the size of disp0GT.pfm")
        bs, bd = bad_of(stereo, gt), bad_of(decoded, gt)
        changed = ~((stereo == decoded) | (np.isnan(stereo) & np.isnan(decoded)))
        masks = dict(masks, all=np.isfinite(gt))
        for r in ROWS:
            m = masks[r]
            totals[r] += [m.sum(), (bs & m).sum(), (bd & m).sum(), (changed & m).sum(), (changed & m & bs).sum()]
            changed_bad_after[r] += int((changed & m & bd).sum())
        if a.flags:
            count_flags(a.flags, name, stereo, bs, masks, flag_totals)
        if a.image:
            rows.append((scene, gt, stereo, decoded, {k: v for k, v in masks.items() if k != "all"}, bs, bd))
    title = f" ({a.label})" if a.label else ""
    print(f"| region{title} | pixels | stereo bad-2 | + decode bad-2 | changed | changed: bad-2 before / after |")
    print("|---|---|---|---|---|---|")
    out = {}
    for r in ROWS:
        n, s, d, c, cb = (int(x) for x in totals[r])
        if n == 0:
            continue
        ca = changed_bad_after[r]
        pct = lambda x, m: 100.0 * x / m if m else float("nan")  # noqa: E731
        print(f"| {r} | {n} | {pct(s, n):.2f} % | {pct(d, n):.2f} % | {c} | "
              f"{pct(cb, c):.0f} / {pct(ca, c):.0f} % |")
        out[r] = {"pixels": n, "stereo_bad2": pct(s, n), "decoded_bad2": pct(d, n), "changed": c,
                  "changed_bad2_before": pct(cb, c), "changed_bad2_after": pct(ca, c)}
    if a.flags:
        print_flags(flag_totals, title)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)
    if a.image:
        write_image(a.image, rows)


def count_flags(folder, name, stereo, bs, masks, totals):
    from PIL import Image
    path = os.path.join(folder, name + "_check.png")
    if not os.path.isfile(path):
        fail(f"{path} is missing")
    flagged = np.asarray(Image.open(path)) > 0
    if flagged.shape != stereo.shape:
        fail(f"{path} is not the size of the stereo result")
    bad_finite = bs & np.isfinite(stereo)
    for r in ROWS:
        m = masks[r]
        totals[r] += [(flagged & m).sum(), (flagged & m & bs).sum(), (bad_finite & m).sum(),
                      (np.isfinite(stereo) & m).sum()]


def print_flags(totals, title):
    print(f"\n| region{title} | flagged | precision | recall (of bad-2 with a stereo value) | "
          "bad-2 of the finite values: all / unflagged |")
    print("|---|---|---|---|---|")
    for r in ROWS:
        f, fb, b, n = (int(x) for x in totals[r])
        if f == 0 and b == 0:
            continue
        pct = lambda x, m: 100.0 * x / m if m else float("nan")  # noqa: E731
        print(f"| {r} | {f} | {pct(fb, f):.1f} % | {pct(fb, b):.1f} % | {pct(b, n):.2f} / {pct(b - fb, n - f):.2f} % |")


def write_image(path, rows):
    import cv2
    from PIL import Image
    sys.path.insert(0, os.path.join(HERE, "..", "stereo"))
    from make_montage import save, sheet, tile
    width = 240
    grid = []
    for scene, gt, stereo, decoded, masks, bs, bd in rows:
        left = cv2.imread(os.path.join(scene, "im0.png"))[:, :, ::-1]
        tiles = [("left view", left), ("stereo: bad-2 by region", error_by_region(masks, bs)),
                 ("stereo + decode: bad-2 by region", error_by_region(masks, bd))]
        grid.append((os.path.basename(os.path.normpath(scene)), [(label, tile(Image.fromarray(np.ascontiguousarray(img)), width=width)) for label, img in tiles]))
    save(sheet(grid), path)


if __name__ == "__main__":
    main()

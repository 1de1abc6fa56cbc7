#!/usr/bin/python3
"""Pick's stereo plans scored on the parts (docs/pick.md, "Stereo where it matters").

usage: scripts/stereo/stereo_plan_report.py BIN_DIR [BIN_DIR ...] --out DIR
           [--bench build/bench/flexsight_bench_stereo_plan] [--plans full1,...,refine4]
           [--min-visib 0.5] [--bench-args '--region-coarsest 128 ...']
           [--picture FILE.jpg] [--models-info FILE]

Each bin (MiddEval3 layout with BOP ground truth: disp0GT.pfm, mask0nocc.png,
mask_visib/, scene_gt_info.json) is run through flexsight_bench_stereo_plan into
DIR/<bin>/ (skipped when DIR/<bin>/times.tsv already lists every plan), with the boxes
(bbox_visib) of its parts at least --min-visib visible as the boxes refine4 refines.
Printed: per plan the median wall and CPU seconds over the bins and bad-2 (|d - gt| > 2
px, a non-finite result counts as bad) on the parts' pixels that both cameras see (all
parts, and inside the refined boxes); per box the median wall and CPU seconds and size.
DIR/report.json holds every figure per bin. --picture: the first bin's left view with the
bin's region (roi4's rectangle) and the refined boxes, and per plan full1, roi4, refine4
(those run) the parts' pixels more than 2 px off in red, the others in green.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pfm_io import read_pfm  # noqa: E402


def part_masks(bin_dir):
    """Union of the parts' visible masks that both cameras see, with finite ground truth."""
    gt = read_pfm(os.path.join(bin_dir, "disp0GT.pfm"))
    nocc = cv2.imread(os.path.join(bin_dir, "mask0nocc.png"), cv2.IMREAD_GRAYSCALE) == 255
    parts = np.zeros(gt.shape, bool)
    folder = os.path.join(bin_dir, "mask_visib")
    for name in sorted(os.listdir(folder)):
        parts |= cv2.imread(os.path.join(folder, name), cv2.IMREAD_GRAYSCALE) > 0
    return gt, parts & nocc & np.isfinite(gt) & (gt > 0)


def boxes_of(bin_dir, min_visib, models_info):
    """The visible boxes of the parts at least min_visib visible, each with its part's
    diameter (mm)."""
    with open(os.path.join(bin_dir, "scene_gt_info.json")) as f:
        info = next(iter(json.load(f).values()))
    with open(os.path.join(bin_dir, "scene_gt.json")) as f:
        gt = next(iter(json.load(f).values()))
    with open(models_info) as f:
        diameters = {int(k): v["diameter"] for k, v in json.load(f).items()}
    return [e["bbox_visib"] + [diameters[g["obj_id"]]] for e, g in zip(info, gt)
            if e["visib_fract"] >= min_visib and e["bbox_visib"][2] > 0]


def bad2(result, gt, mask):
    if mask.sum() == 0:
        return None
    err = np.abs(result[mask] - gt[mask])
    return float(np.mean(~(err <= 2.0)))


def picture(bin_dir, out, plans, path):
    """A row of panels at 1/4 size: the left view with the region and boxes, then per plan
    the parts' pixels coloured by error."""
    left = cv2.imread(os.path.join(bin_dir, "im0.png"))
    gt, parts = part_masks(bin_dir)
    times = {l.split("\t")[0]: l.rstrip("\n").split("\t") for l in open(os.path.join(out, "times.tsv"))}
    first = left.copy()
    if "roi4" in times:
        x, y, w, h = map(int, times["roi4"][4].split(","))
        cv2.rectangle(first, (x, y), (x + w - 1, y + h - 1), (255, 200, 0), 6)
    for x, y, w, h in (tuple(map(int, l.split()[:4])) for l in open(os.path.join(out, "boxes.txt"))):
        cv2.rectangle(first, (x, y), (x + w - 1, y + h - 1), (0, 220, 255), 3)
    panels = [first]
    for plan in [p for p in ("full1", "roi4", "refine4") if p in plans and p in times]:
        result = read_pfm(os.path.join(out, plan + ".pfm"))
        panel = (left * 0.35).astype(np.uint8)
        bad = parts & ~(np.abs(result - gt) <= 2.0)
        panel[parts & ~bad] = (0, 200, 0)
        panel[bad] = (0, 0, 255)
        cv2.putText(panel, plan, (20, 70), cv2.FONT_HERSHEY_SIMPLEX, 2.2, (255, 255, 255), 4)
        panels.append(panel)
    row = np.hstack([cv2.resize(p, None, fx=0.25, fy=0.25, interpolation=cv2.INTER_AREA) for p in panels])
    cv2.imwrite(path, row, [cv2.IMWRITE_JPEG_QUALITY, 80])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bins", nargs="+")
    ap.add_argument("--out", required=True)
    ap.add_argument("--bench", default="build/bench/flexsight_bench_stereo_plan")
    ap.add_argument("--plans", default="full1,full2,full4,roi1,roi2,roi4,refine4")
    ap.add_argument("--min-visib", type=float, default=0.5)
    ap.add_argument("--bench-args", default="", help="more arguments for the bench, e.g. '--region-coarsest 128'")
    ap.add_argument("--picture")
    ap.add_argument("--models-info", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                                          "models", "tless-cad", "models_info.json"),
                    help="the parts' diameters (BOP models_info.json)")
    args = ap.parse_args()
    plans = args.plans.split(",")
    report = {}
    for bin_dir in args.bins:
        name = os.path.basename(os.path.normpath(bin_dir))
        parent = os.path.basename(os.path.dirname(os.path.normpath(bin_dir)))
        out = os.path.join(args.out, parent + "_" + name)
        os.makedirs(out, exist_ok=True)
        boxes = boxes_of(bin_dir, args.min_visib, args.models_info)
        with open(os.path.join(out, "boxes.txt"), "w") as f:
            f.writelines("%d %d %d %d %.1f\n" % tuple(b) for b in boxes)
        times_path = os.path.join(out, "times.tsv")
        done = [l.split("\t")[0] for l in open(times_path)] if os.path.exists(times_path) else []
        if any(p not in done for p in plans):
            subprocess.run([args.bench, bin_dir, out, "--boxes", os.path.join(out, "boxes.txt"),
                            "--plans", ",".join(plans)] + args.bench_args.split(), check=True)
        gt, parts = part_masks(bin_dir)
        in_boxes = np.zeros(gt.shape, bool)
        for x, y, w, h, _ in boxes:
            in_boxes[y:y + h, x:x + w] = True
        entry = {"plans": {}, "boxes": []}
        for line in open(times_path):
            plan, coarse, total, cpu, rect, rng = line.rstrip("\n").split("\t")
            result = read_pfm(os.path.join(out, plan + ".pfm"))
            entry["plans"][plan] = {"wall_s": float(total), "wall_coarse_s": float(coarse), "cpu_s": float(cpu),
                                    "rect": rect, "range": rng, "bad2_parts": bad2(result, gt, parts),
                                    "bad2_parts_in_boxes": bad2(result, gt, parts & in_boxes)}
        boxes_tsv = os.path.join(out, "boxes.tsv")
        if os.path.exists(boxes_tsv):
            for line in open(boxes_tsv):
                x, y, w, h, crop, ndisp, wall, cpu = line.split("\t")
                entry["boxes"].append({"box": [int(x), int(y), int(w), int(h)], "crop": crop, "ndisp": int(ndisp),
                                       "wall_s": float(wall), "cpu_s": float(cpu)})
        report[parent + "/" + name] = entry
    if args.picture:
        first = os.path.normpath(args.bins[0])
        picture(first, os.path.join(args.out, os.path.basename(os.path.dirname(first)) + "_" +
                                    os.path.basename(first)), plans, args.picture)
    with open(os.path.join(args.out, "report.json"), "w") as f:
        json.dump(report, f, indent=1)

    def med(values):
        values = [v for v in values if v is not None]
        return statistics.median(values) if values else float("nan")

    print("| plan | wall s (median) | CPU s (median) | bad-2 on the parts | bad-2 on the parts in the boxes |")
    print("|---|---|---|---|---|")
    for plan in plans:
        rows = [e["plans"][plan] for e in report.values() if plan in e["plans"]]
        print("| %s | %.2f | %.2f | %.2f %% | %.2f %% |" % (
            plan, med([r["wall_s"] for r in rows]), med([r["cpu_s"] for r in rows]),
            100 * med([r["bad2_parts"] for r in rows]), 100 * med([r["bad2_parts_in_boxes"] for r in rows])))
    boxes = [b for e in report.values() for b in e["boxes"]]
    if boxes:
        print("\nboxes: %d, median %dx%d px, wall %.3f s, CPU %.3f s each (median), ndisp %d" % (
            len(boxes), med([b["box"][2] for b in boxes]), med([b["box"][3] for b in boxes]),
            med([b["wall_s"] for b in boxes]), med([b["cpu_s"] for b in boxes]), med([b["ndisp"] for b in boxes])))
    for key, e in report.items():
        print(key, " ".join("%s=%.1f%%/%.1fs" % (p, 100 * (r["bad2_parts"] or 0), r["wall_s"])
                            for p, r in e["plans"].items()), e["plans"].get("roi4", {}).get("rect", ""),
              e["plans"].get("roi4", {}).get("range", ""))


if __name__ == "__main__":
    main()

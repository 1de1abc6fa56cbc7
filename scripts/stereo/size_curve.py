#!/usr/bin/python3
"""Time, memory and accuracy of the matcher against image size, on projector-lit bins
rendered by `flexsight synth bin` at each size (the same scene at every size: the piles
depend on the seed only, the focal length follows the image size).

usage: scripts/stereo/size_curve.py --out DIR [--flexsight build/flexsight]
         [--sizes 816x612,1152x864,2000x1500,4000x3000] [--bins 2] [--seed 300]
         [--bins-root DIR] [-- extra flexsight stereo options]

Writes DIR/size_curve.json, DIR/size_curve.md and DIR/size_curve.png (docs/stereo.md,
"12 MP"). Each pair runs in its own process, so its peak resident memory (from wait4)
is the whole run's: images, the OpenCL runtime, device buffers (PoCL's live in host
memory) and the post-processing.
Accuracy, among the pixels with ground truth: bad-2 at the image's own pixel size (a
2-px error is a smaller depth error at 12 MP than at 0.5 MP), bad-2 of the 1152-px-wide
image's pixel (the threshold scaled with the width: the same depth tolerance at every
size), the parts' bad-2 (scripts/stereo/bins_figures.py's classes) and the median depth
error in mm.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bins_figures import pixel_classes  # noqa: E402
from pfm_io import read_pfm  # noqa: E402

REFERENCE_WIDTH = 1152  # about 1 MP at 4:3


def read_calib(scene):
    values = {}
    for line in open(os.path.join(scene, "calib.txt")):
        key, _, value = line.partition("=")
        values[key.strip()] = value.strip()
    focal = float(values["cam0"].strip("[]").split()[0])
    return focal, float(values["baseline"]), float(values["doffs"])


def run_measured(cmd, log_path):
    """Runs cmd; returns (wall seconds, peak RSS in MiB, stdout)."""
    start = time.monotonic()
    with open(log_path, "w") as log:
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=log, text=True)
        out = proc.stdout.read()
        _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - start
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"size_curve: {' '.join(cmd)} failed (see {log_path})")
    return wall, usage.ru_maxrss / 1024.0, out


def accuracy(scene, disp_path):
    gt, classes = pixel_classes(scene)
    disp = read_pfm(disp_path)
    width = gt.shape[1]
    with np.errstate(invalid="ignore"):
        err = np.abs(disp - gt)
    err[~np.isfinite(disp)] = np.inf
    all_px = classes["all"]
    parts = classes["parts"]
    focal, baseline, doffs = read_calib(scene)
    ok = all_px & np.isfinite(disp)
    z_gt = focal * baseline / (gt[ok] + doffs)
    z = focal * baseline / (disp[ok] + doffs)
    return {
        "bad2_all": float((err[all_px] > 2.0).mean() * 100.0),
        "bad2_parts": float((err[parts] > 2.0).mean() * 100.0),
        "bad2_1mp_pixel_all": float((err[all_px] > 2.0 * width / REFERENCE_WIDTH).mean() * 100.0),
        "bad2_1mp_pixel_parts": float((err[parts] > 2.0 * width / REFERENCE_WIDTH).mean() * 100.0),
        "median_depth_error_mm": float(np.median(np.abs(z - z_gt))),
    }


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sizes = sorted({r["megapixels"] for r in rows})

    def mean_of(key):
        return [np.mean([r[key] for r in rows if r["megapixels"] == s]) for s in sizes]

    fig, ax = plt.subplots(1, 3, figsize=(13, 3.8))
    ax[0].plot(sizes, mean_of("seconds"), "o-")
    ax[0].set_ylabel("seconds per pair")
    ax[1].plot(sizes, [m / 1024 for m in mean_of("peak_rss_mib")], "o-", label="process peak")
    ax[1].plot(sizes, [m / 1024 for m in mean_of("device_buffers_mib")], "s--", label="device buffers")
    ax[1].axhline(8, color="r", lw=1, label="8 GB")
    ax[1].set_ylabel("GiB")
    ax[1].legend()
    ax[2].plot(sizes, mean_of("bad2_all"), "o-", label="bad-2 all (own pixel)")
    ax[2].plot(sizes, mean_of("bad2_1mp_pixel_all"), "s--", label="bad-2 all (1 MP pixel)")
    ax[2].plot(sizes, mean_of("bad2_parts"), "^-", label="bad-2 parts (own pixel)")
    ax[2].set_ylabel("%")
    ax[2].legend(fontsize=8)
    for a in ax:
        a.set_xscale("log")
        a.set_xticks(sizes)
        a.set_xticklabels([f"{s:.1f}" for s in sizes])
        a.set_xlabel("megapixels")
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=90)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--out", required=True)
    p.add_argument("--flexsight", default="build/flexsight")
    p.add_argument("--sizes", default="816x612,1152x864,2000x1500,4000x3000")
    p.add_argument("--bins", type=int, default=2)
    p.add_argument("--seed", type=int, default=300)
    p.add_argument("--bins-root", default=None, help="rendered bins (default OUT/bins)")
    p.add_argument("stereo_options", nargs="*", help="after --: options for flexsight stereo")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    bins_root = args.bins_root or os.path.join(args.out, "bins")
    os.makedirs(bins_root, exist_ok=True)
    stereo_options = args.stereo_options or ["--preset", "active"]
    rows = []
    sizes = args.sizes.split(",")
    for size in sizes:
        folder = os.path.join(bins_root, size)
        if not os.path.isdir(folder):
            print(f"size_curve: rendering {args.bins} bins at {size}", flush=True)
            subprocess.run([args.flexsight, "synth", "bin", "--count", str(args.bins), "--seed", str(args.seed),
                            "--size", size, "-o", folder], check=True, stdout=subprocess.DEVNULL)
        w, h = (int(v) for v in size.split("x"))
        for b in range(args.bins):
            scene = os.path.join(folder, f"bin{b:03d}")
            disp = os.path.join(args.out, f"{size}_bin{b:03d}.pfm")
            print(f"size_curve: {size} bin {b + 1} of {args.bins}", flush=True)
            wall, rss, out = run_measured([args.flexsight, "stereo", scene, "-o", disp, "--quiet", "--profile"] + stereo_options,
                                          os.path.join(args.out, f"{size}_bin{b:03d}.log"))
            device = re.search(r"device memory: ([0-9.]+) MiB", out)
            row = {"size": size, "megapixels": w * h / 1e6, "bin": b, "seconds": wall, "peak_rss_mib": rss,
                   "device_buffers_mib": float(device.group(1)) if device else 0.0}
            row.update(accuracy(scene, disp))
            print(f"  {wall:.1f} s, peak {rss:.0f} MiB, bad-2 {row['bad2_all']:.2f} %", flush=True)
            rows.append(row)
    cpu = "unknown CPU"
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
    summary = {"cpu": cpu, "cores": os.cpu_count(), "stereo_options": stereo_options, "rows": rows}
    with open(os.path.join(args.out, "size_curve.json"), "w") as f:
        json.dump(summary, f, indent=1)
    keys = ["seconds", "peak_rss_mib", "device_buffers_mib", "bad2_all", "bad2_1mp_pixel_all", "bad2_parts",
            "bad2_1mp_pixel_parts", "median_depth_error_mm"]
    with open(os.path.join(args.out, "size_curve.md"), "w") as f:
        f.write(f"{cpu}, {os.cpu_count()} cores; flexsight stereo {' '.join(stereo_options)}; "
                f"mean of {args.bins} bins per size\n\n")
        f.write("| size | MP | " + " | ".join(keys) + " |\n|---|---:|" + "---:|" * len(keys) + "\n")
        for size in sizes:
            sel = [r for r in rows if r["size"] == size]
            f.write(f"| {size} | {sel[0]['megapixels']:.2f} | " +
                    " | ".join(f"{np.mean([r[k] for r in sel]):.2f}" for k in keys) + " |\n")
    plot(rows, os.path.join(args.out, "size_curve.png"))
    print(open(os.path.join(args.out, "size_curve.md")).read())


if __name__ == "__main__":
    main()

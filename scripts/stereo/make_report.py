#!/usr/bin/python3
"""Writes the benchmark report (Markdown, pictures, JSON copies) from the `flexsight eval`
runs that scripts/stereo/benchmark_report.sh made. Numbers come only from those runs.

usage: make_report.py --runs DIR --out DIR --middlebury ROOT [--kitti ROOT] --montage A,B
                      --repeat N --reference-scenes A,B --flexsight BINARY

The tables are built in report_tables.py and the figures drawn in report_plots.py, both
imported from this script's folder as pfm_io is.
"""
import argparse
import datetime
import os
import platform
import shutil
import subprocess

import numpy as np
from PIL import Image

from pfm_io import read_pfm
from report_plots import montage, plot_runtime_vs_bad2, plot_sparsification
from report_tables import (LABEL, averages, depth_table, fmt, load_runs, per_scene_table,
                           sparsification_rows, table_one, table_subset, table_two)


def command_output(command):
    try:
        return subprocess.run(command, capture_output=True, text=True, check=False).stdout.strip()
    except OSError:
        return ""


def machine_lines(flexsight, commit):
    cpu = ""
    for line in command_output(["lscpu"]).splitlines():
        if line.startswith("Model name"):
            cpu = line.split(":", 1)[1].strip()
    # The device rows of the table `flexsight devices` prints.
    devices = [l for l in command_output([flexsight, "devices"]).splitlines()
               if l.startswith("| ") and l[2:3].isdigit()]
    return [
        f"- Machine: {cpu or platform.processor()}, {os.cpu_count()} cores visible, {platform.system()} {platform.release()}",
        "- OpenCL devices (`flexsight devices`):",
        *[f"  - {d.strip('| ').replace(' | ', ', ')}" for d in devices[:6]],
        f"- Commit: {commit} (the build the runs used)",
        f"- Date: {datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d %H:%M UTC')}",
    ]


def current_commit():
    commit = command_output(["git", "rev-parse", "--short", "HEAD"])
    dirty = command_output(["git", "status", "--porcelain", "--untracked-files=no"])
    return f"`{commit}`" + (" with uncommitted changes" if dirty else "")


def ratio(a, b):
    return None if not a or not b else a / b


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--runs", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--middlebury", required=True)
    parser.add_argument("--kitti")
    parser.add_argument("--montage", default="Teddy,Motorcycle,PianoL")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--reference-scenes", default="ArtL,Teddy,Motorcycle")
    parser.add_argument("--flexsight", default="build/flexsight")
    parser.add_argument("--commit", help="the commit the runs were built from (default: HEAD now)")
    args = parser.parse_args()
    os.makedirs(os.path.join(args.out, "json"), exist_ok=True)

    mb = load_runs(args.runs, "middlebury")
    names = [s["name"] for s in mb["ppms-opencl"]["scenes"]]
    subset = [n for n in args.reference_scenes.split(",") if n in names]
    for key, report in mb.items():
        shutil.copy(os.path.join(args.runs, f"middlebury-{key}", "report.json"),
                    os.path.join(args.out, "json", f"middlebury-{key}.json"))

    plot_runtime_vs_bad2(mb, os.path.join(args.out, "runtime_vs_bad2.png"), names, subset)
    has_sparsification = plot_sparsification(mb, os.path.join(args.out, "sparsification.png"), names)
    pictures = []
    for scene in args.montage.split(","):
        if scene not in names:
            continue
        calib = open(os.path.join(args.middlebury, scene, "calib.txt")).read()
        ndisp = int([l for l in calib.splitlines() if l.startswith("ndisp")][0].split("=")[1])
        path = f"montage_{scene}.jpg"
        montage(mb, args.runs, "middlebury", args.middlebury, scene, os.path.join(args.out, path),
                os.path.join(args.middlebury, scene, "im0.png"),
                lambda s=scene: read_pfm(os.path.join(args.middlebury, s, "disp0GT.pfm")), ndisp)
        pictures.append((scene, path))

    # Ratios the stereo issues set as targets, from this run.
    a = {k: averages(r, "all") for k, r in mb.items()}
    s = {k: averages(r, "all", subset) for k, r in mb.items()}
    ratios = [
        ("PPMS vs PMS runtime, OpenCL, all scenes (target >= 2.5x)",
         ratio(a.get("pms-opencl", {}).get("seconds"), a["ppms-opencl"]["seconds"]), "x"),
        (f"PPMS vs PMS runtime, reference path, {len(subset)} scenes",
         ratio(s.get("pms-reference", {}).get("seconds"), s.get("ppms-reference", {}).get("seconds")), "x"),
        (f"OpenCL vs reference runtime, PPMS, {len(subset)} scenes (target >= 8x on 2 cores)",
         ratio(s.get("ppms-reference", {}).get("seconds"), s["ppms-opencl"]["seconds"]), "x"),
        ("PPMS fast preset runtime, OpenCL, all scenes (s; target <= 2 s on 2 cores)",
         a.get("ppms-fast-opencl", {}).get("seconds"), " s"),
        ("PPMS fast preset bad-2 (all), all scenes (%; target < 12 %)",
         a.get("ppms-fast-opencl", {}).get("bad", {}).get("2"), " %"),
        (f"OpenCL vs reference runtime, PPMS fast preset, {len(subset)} scenes",
         ratio(s.get("ppms-fast-reference", {}).get("seconds"),
               s.get("ppms-fast-opencl", {}).get("seconds")), "x"),
        ("PPMS bad-2 (all) / StereoSGBM bad-2 (all), all scenes",
         ratio(a["ppms-opencl"]["bad"]["2"], a.get("opencv-sgbm", {}).get("bad", {}).get("2")), ""),
        ("PPMS bad-2 (all) minus PMS bad-2 (all), all scenes (points)",
         a["ppms-opencl"]["bad"]["2"] - a["pms-opencl"]["bad"]["2"] if "pms-opencl" in a else None, " pt"),
    ]

    reference_seconds = s.get("ppms-reference", {}).get("seconds")
    reference_note = ("it is the slow path" if reference_seconds is None else
                      f"PPMS took {reference_seconds:.1f} s per scene there in this run, on 2 cores")
    text = ["# Benchmark report: FlexSight PPMS/PMS against OpenCV's matchers", "",
            "Produced by one run of", "",
            "```sh",
            f"scripts/stereo/benchmark_report.sh {args.middlebury}" + (f" {args.kitti}" if args.kitti else ""),
            "```", "",
            *machine_lines(args.flexsight, args.commit or current_commit()), "",
            "## Conventions", "",
            f"- Middlebury 2014 training set at quarter resolution (MiddEval3 `trainingQ`, {len(names)} scenes), "
            "errors in pixels at that resolution (bad 2 here is bad 8 at full resolution); "
            "'all' = every pixel with ground truth, 'nonocc' = `mask0nocc.png` = 255.",
            "- Pixels without a result count as bad (MiddEval3 SDK convention); our matchers are dense, "
            "OpenCV's leave holes (see the density column of the JSON).",
            "- Averages are unweighted means over scenes. Runtime: wall time of the matcher per scene "
            f"(images in memory; no file I/O), the median of {args.repeat} runs per scene for PPMS "
            "(OpenCL) and OpenCV's matchers, one run otherwise. The table's 'median' column is the "
            "median over scenes.",
            f"- The reference C++ path runs on {', '.join(subset)} only ({reference_note}).",
            "- The same PatchMatch parameters for every run (the defaults of `host/stereo/stereo_params.h`), "
            "except the fast preset's rows (`--preset fast`: sparser windows and one iteration per finer "
            "level, `apply_stereo_preset`). "
            "OpenCV: " + "StereoSGBM MODE_SGBM_3WAY, block 5, P1 8*3*25, P2 32*3*25, uniqueness 10, "
            "speckle 100/2; StereoBM block 9 with the settings of OpenCV's stereo_match sample "
            "(`host/stereo/opencv_stereo.h`).",
            "- The OpenCL path ran on PoCL (the CPU) of this machine; there was no GPU in this run.", "",
            "## Table I format: Middlebury 2014 training, quarter resolution, all pixels", "",
            table_one(mb, "all", names), "",
            "## Table I format: non-occluded pixels", "",
            table_one(mb, "nonocc", names), "",
            f"## The same on the reference path's scenes ({', '.join(subset)}), all pixels", "",
            table_subset(mb, "all", subset), "",
            "## Ratios from this run", "",
            "| ratio | value |", "|---|---:|",
            *[f"| {label} | {fmt(value)}{unit if value is not None else ''} |" for label, value, unit in ratios], "",
            "## Runtime against bad 2", "",
            "![runtime against bad 2](runtime_vs_bad2.png)", "",
            "## Per scene: bad 2 (all pixels) and runtime", "",
            per_scene_table(mb, names), "",
            "## Median absolute depth error (mm), all pixels with ground truth", "",
            "Our depth against the depth of the ground-truth disparity through the scene's calib.txt "
            "(Z = baseline f / (d + doffs)); a pixel without a result counts as an infinite error, so a "
            "method that leaves more than half the pixels empty has no finite median. The last two "
            "columns: PPMS (OpenCL) over the pixels whose confidence is at least 0.5, and their share.", "",
            depth_table(mb, names), ""]
    if has_sparsification:
        text += ["## Confidence: sparsification", "",
                 "Each method's pixels ranked by its confidence map (host/stereo/confidence_map.h), "
                 "the bad-2 of the most confident 5, 10, ..., 100 % (all pixels with ground truth), "
                 "averaged over the scenes; the area is the mean of that curve (lower is better), "
                 "the optimum ranks by the true error.", "",
                 "| method | sparsification AUC, bad 2 (%) | optimal AUC (%) |", "|---|---:|---:|",
                 *[f"| {LABEL[key]} | {fmt(auc)} | {fmt(best)} |"
                   for key, auc, best in sparsification_rows(mb, names)], "",
                 "![sparsification](sparsification.png)", ""]
    text += ["## Pictures", "",
            "Top row: left image, ground truth, each method's disparity (same colour scale, black = no "
            "result). Bottom row: error maps (green within 2 px, yellow to red worse, magenta no result, "
            "black no ground truth).", ""]
    for scene, path in pictures:
        text += [f"### {scene}", "", f"![{scene}]({path})", ""]

    if args.kitti:
        kt = load_runs(args.runs, "kitti")
        for key in kt:
            shutil.copy(os.path.join(args.runs, f"kitti-{key}", "report.json"),
                        os.path.join(args.out, "json", f"kitti-{key}.json"))
        kitti_scene = kt["ppms-opencl"]["scenes"][0]["name"]
        text += ["## Table II format: KITTI 2012 training pair " + kitti_scene, "",
                 "Sparse LiDAR ground truth (`disp_occ` for all, `disp_noc` for non-occluded), ndisp 256, "
                 "one pair only: indicative, not a KITTI score.", "",
                 table_two(kt), ""]
        path = "montage_kitti.jpg"
        montage(kt, args.runs, "kitti", args.kitti, kitti_scene, os.path.join(args.out, path),
                os.path.join(args.kitti, "training", "colored_0", kitti_scene + ".png"),
                lambda: kitti_ground_truth(args.kitti, kitti_scene), 128)
        text += [f"![KITTI {kitti_scene}]({path})", ""]

    with open(os.path.join(args.out, "README.md"), "w") as f:
        f.write("\n".join(text))


def kitti_ground_truth(root, scene):
    raw = np.asarray(Image.open(os.path.join(root, "training", "disp_occ", scene + ".png")), dtype=np.float32)
    return np.where(raw > 0, raw / 256.0, np.inf)


if __name__ == "__main__":
    main()

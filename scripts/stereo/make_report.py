#!/usr/bin/python3
"""Writes the benchmark report (Markdown, pictures, JSON copies) from the `flexsight eval`
runs that scripts/stereo/benchmark_report.sh made. Numbers come only from those runs.

usage: make_report.py --runs DIR --out DIR --middlebury ROOT [--kitti ROOT] --montage A,B
                      --repeat N --reference-scenes A,B --flexsight BINARY
"""
import argparse
import datetime
import json
import os
import platform
import shutil
import statistics
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image, ImageDraw  # noqa: E402

from pfm_io import read_pfm  # noqa: E402

# Report order, with the words a reader sees.
METHODS = [
    ("ppms-opencl", "PPMS (ours, OpenCL)"),
    ("pms-opencl", "PMS (ours, OpenCL)"),
    ("ppms-reference", "PPMS (ours, reference C++)"),
    ("ppms-fast-opencl", "PPMS fast preset (ours, OpenCL)"),
    ("ppms-fast-reference", "PPMS fast preset (ours, reference C++)"),
    ("pms-reference", "PMS (ours, reference C++)"),
    ("opencv-sgbm", "OpenCV StereoSGBM (3-way)"),
    ("opencv-bm", "OpenCV StereoBM"),
]
LABEL = dict(METHODS)
# Same bytes as their OpenCL run (the byte tests prove it): one picture is enough.
NOT_IN_MONTAGE = {"ppms-fast-reference"}


def load_runs(runs, dataset):
    found = {}
    for key, _ in METHODS:
        path = os.path.join(runs, f"{dataset}-{key}", "report.json")
        if os.path.exists(path):
            with open(path) as f:
                found[key] = json.load(f)
    return found


def scenes_of(report):
    return {scene["name"]: scene for scene in report["scenes"]}


def mean(values):
    values = [v for v in values if v is not None]
    return sum(values) / len(values) if values else None


def fmt(value, decimals=2):
    return "-" if value is None else f"{value:.{decimals}f}"


def seconds_cell(value):
    if value is None:
        return "-"
    return f"{value * 1000:.1f} ms" if value < 1 else f"{value:.2f} s"


def averages(report, region, names=None):
    scenes = [s for s in report["scenes"] if names is None or s["name"] in names]
    return {
        "bad": {t: mean([s[region][f"bad_{t}"] for s in scenes]) for t in ("0.5", "1", "2", "3", "4")},
        "seconds": mean([s["seconds"] for s in scenes]),
        "median_seconds": statistics.median([s["seconds"] for s in scenes]) if scenes else None,
        "count": len(scenes),
    }


def ran(runs):
    """(key, label) of each method in `runs`, in report order."""
    return [(key, label) for key, label in METHODS if key in runs]


def markdown_table(header, rows):
    """A Markdown table: the first column left-aligned, the others right-aligned."""
    lines = ["| " + " | ".join(header) + " |", "|---|" + "---:|" * (len(header) - 1)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)


def bad_cells(a, thresholds):
    """The cells of the bad-t averages of `a`, for each threshold t."""
    return [fmt(a["bad"][t]) for t in thresholds]


def table_one(runs, region, all_names):
    """The paper's Table I: bad 0.5 / 1 / 2 / 4 and runtime, averaged over scenes."""
    rows = []
    for key, label in ran(runs):
        a = averages(runs[key], region)
        subset = "all" if a["count"] == len(all_names) else f"{a['count']}"
        rows.append([label, subset, *bad_cells(a, ("0.5", "1", "2", "4")),
                     seconds_cell(a["seconds"]), seconds_cell(a["median_seconds"])])
    return markdown_table(["method", "scenes", "bad 0.5 (%)", "bad 1 (%)", "bad 2 (%)", "bad 4 (%)",
                           "runtime (mean)", "runtime (median)"], rows)


def table_subset(runs, region, names):
    """All methods on the scenes the reference path ran on, so the rows compare."""
    rows = []
    for key, label in ran(runs):
        a = averages(runs[key], region, names)
        rows.append([label, *bad_cells(a, ("0.5", "1", "2", "4")), seconds_cell(a["seconds"])])
    return markdown_table(["method", "bad 0.5 (%)", "bad 1 (%)", "bad 2 (%)", "bad 4 (%)",
                           "runtime (mean)"], rows)


def table_two(runs):
    """The paper's Table II for KITTI: bad 2 / 3 and runtime, all (occ) and noc."""
    rows = []
    for key, label in ran(runs):
        a, n = averages(runs[key], "all"), averages(runs[key], "nonocc")
        density = mean([s["all"]["density"] for s in runs[key]["scenes"]])
        rows.append([label, *bad_cells(a, ("2", "3")), *bad_cells(n, ("2", "3")), fmt(density, 1),
                     seconds_cell(a["seconds"])])
    return markdown_table(["method", "bad 2 all (%)", "bad 3 all (%)", "bad 2 noc (%)",
                           "bad 3 noc (%)", "density (%)", "runtime"], rows)


def per_scene_table(runs, names):
    header = "| scene | " + " | ".join(f"{LABEL[k]} bad 2 all (%) / time" for k, _ in METHODS if k in runs) + " |"
    rule = "|---|" + "---:|" * sum(1 for k, _ in METHODS if k in runs)
    lines = [header, rule]
    for name in names:
        cells = []
        for key, _ in METHODS:
            if key not in runs:
                continue
            scene = scenes_of(runs[key]).get(name)
            cells.append("-" if scene is None else f"{scene['all']['bad_2']:.2f} / {seconds_cell(scene['seconds'])}")
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def depth_table(runs, names):
    keys = [k for k, _ in METHODS if k in runs]
    header = ("| scene | " + " | ".join(f"{LABEL[k]}" for k in keys) +
              " | PPMS (OpenCL), pixels with C >= 0.5 | share of pixels with C >= 0.5 (%) |")
    lines = [header, "|---|" + "---:|" * (len(keys) + 2)]
    for name in names:
        cells = []
        for key in keys:
            scene = scenes_of(runs[key]).get(name)
            value = scene.get("depth_mm", {}).get("median_abs_all") if scene else None
            cells.append(fmt(value, 1))
        ours = scenes_of(runs.get("ppms-opencl", {"scenes": []})).get(name, {})
        confident = ours.get("depth_mm", {}).get("median_abs_confident")
        share = ours.get("confident", {}).get("density", [None, None])[1]
        lines.append(f"| {name} | " + " | ".join(cells) + f" | {fmt(confident, 1)} | {fmt(share, 1)} |")
    return "\n".join(lines)


def plot_runtime_vs_bad2(runs, path, all_names, subset):
    """Left: methods run on every scene. Right: every method on the reference path's scenes."""
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), dpi=110, sharey=False)
    panels = [(axes[0], None, f"all {len(all_names)} scenes"),
              (axes[1], subset, "the reference path's scenes: " + ", ".join(subset))]
    for ax, names, title in panels:
        times = []
        for index, (key, label) in enumerate(METHODS):
            if key not in runs:
                continue
            a = averages(runs[key], "all", names)
            if names is None and a["count"] != len(all_names):
                continue  # a subset average would not compare with the others
            if not a["count"]:
                continue
            times.append(a["seconds"])
            # OpenCL and reference runs give the same bytes, hence the same height, and
            # the PatchMatch variants sit close together: a legend keeps every name
            # readable where labels beside the points would overlap. Reference runs are
            # hollow, so an OpenCL point and its reference twin tell apart.
            hollow = "reference" in key
            ax.scatter(a["seconds"], a["bad"]["2"], s=60, label=label,
                       facecolors="none" if hollow else f"C{index}", edgecolors=f"C{index}",
                       linewidths=1.5)
        ax.legend(fontsize=7, loc="upper right")
        ax.set_xscale("log")
        if times:
            ax.set_xlim(min(times) / 3, max(times) * 3)
        ax.set_xlabel("runtime per scene (s, log scale; this machine)")
        ax.set_ylabel("bad 2, all pixels (%)")
        ax.set_title(title, fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle("Middlebury 2014 training, quarter resolution: average over scenes", fontsize=10)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def mean_curve(report, field):
    """The mean over scenes of a per-scene sparsification curve, or None when a scene lacks it."""
    curves = [scene.get("confident", {}).get(field) for scene in report["scenes"]]
    if not curves or any(c is None for c in curves):
        return None
    return [sum(values) / len(values) for values in zip(*curves)]


def methods_with_confidence(runs, all_names):
    """(colour index, key, label, report) of each method that ran every scene and scored
    a confidence on each (OpenCV's matchers have none)."""
    for index, (key, label) in enumerate(METHODS):
        report = runs.get(key)
        if not report or len(report["scenes"]) != len(all_names):
            continue
        if any("confident" not in scene for scene in report["scenes"]):
            continue
        yield index, key, label, report


def sparsification_rows(runs, all_names):
    """(key, mean AUC, mean optimal AUC) of the methods with a confidence on every scene."""
    rows = []
    for _, key, _, report in methods_with_confidence(runs, all_names):
        auc = [scene["confident"].get("sparsification_auc_bad2") for scene in report["scenes"]]
        best = [scene["confident"].get("optimal_auc_bad2") for scene in report["scenes"]]
        if any(v is None for v in auc + best):
            continue
        rows.append((key, sum(auc) / len(auc), sum(best) / len(best)))
    return rows


def plot_sparsification(runs, path, all_names):
    """bad-2 of the most confident share of the pixels, for each method with a confidence."""
    fig, ax = plt.subplots(figsize=(6.5, 4.2), dpi=110)
    density = [5 * k for k in range(1, 21)]
    plotted = False
    for index, _, label, report in methods_with_confidence(runs, all_names):
        curve = mean_curve(report, "sparsification_curve_bad2")
        optimal = mean_curve(report, "optimal_curve_bad2")
        if curve is None or optimal is None:
            continue
        ax.plot(density, curve, color=f"C{index}", marker="o", markersize=3, label=label)
        ax.plot(density, optimal, color=f"C{index}", linestyle="--", linewidth=1,
                label=label + ", ranked by the true error")
        plotted = True
    if not plotted:
        plt.close(fig)
        return False
    ax.set_xlabel("most confident pixels kept (%)")
    ax.set_ylabel("bad 2 among them, all pixels (%)")
    ax.set_title(f"Sparsification: average over {len(all_names)} scenes", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return True


def colorize(disparity, ndisp):
    valid = np.isfinite(disparity) & (disparity >= 0)
    levels = np.clip(np.where(valid, disparity, 0) / ndisp, 0, 1)
    rgb = (plt.get_cmap("turbo")(levels)[..., :3] * 255).astype(np.uint8)
    rgb[~valid] = 0
    return Image.fromarray(rgb)


def labelled(image, text, scale):
    image = image.convert("RGB")
    image = image.resize((max(1, int(image.width * scale)), max(1, int(image.height * scale))))
    tile = Image.new("RGB", (image.width, image.height + 16), "white")
    tile.paste(image, (0, 16))
    ImageDraw.Draw(tile).text((3, 2), text, fill="black")
    return tile


def montage(runs, runs_dir, dataset, data_root, scene, path, left_name, gt_loader, ndisp):
    keys = [k for k, _ in METHODS
            if k in runs and k not in NOT_IN_MONTAGE and scene in scenes_of(runs[k])]
    left = Image.open(left_name)
    scale = min(1.0, 300 / left.width)
    top = [labelled(left, f"{scene}: left image", scale), labelled(colorize(gt_loader(), ndisp), "ground truth", scale)]
    bottom = [None, None]
    for key in keys:
        folder = os.path.join(runs_dir, f"{dataset}-{key}")
        top.append(labelled(Image.open(os.path.join(folder, f"{scene}_disp.png")), LABEL[key], scale))
        bottom.append(labelled(Image.open(os.path.join(folder, f"{scene}_error.png")), "error map", scale))
    w, h = top[0].width, top[0].height
    sheet = Image.new("RGB", (w * len(top), 2 * h), "white")
    for i, tile in enumerate(top):
        sheet.paste(tile, (i * w, 0))
    for i, tile in enumerate(bottom):
        if tile is not None:
            sheet.paste(tile, (i * w, h))
    sheet.save(path, quality=88)


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

"""The data and Markdown tables of the benchmark report (make_report.py): the methods in
report order, their runs' report.json files, averages over scenes and the tables built
from them."""
import json
import os
import statistics

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

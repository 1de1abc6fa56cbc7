#!/usr/bin/python3
"""Bad-2 by region on every set of bins, with pictures and a Markdown section
(docs/stereo.md, "Bad-2 by region, every set").

usage: scripts/stereo/region_report.py SET[=RESULTS] [SET[=RESULTS] ...] --out DIR
           [--flexsight build/flexsight] [--preset active] [--eval-option ARG ...]
           [--scenes A,B] [--images DIR] [--markdown FILE] [--command TEXT]

SET is a folder of scenes in the MiddEval3 layout (each with disp0GT.pfm; `synth bin`
writes them, ../shared/datasets/active-bins is one). With =RESULTS the disparities are
read from RESULTS/<scene>_disp.pfm (a `flexsight eval --out` folder); without, the
script runs `flexsight eval SET --preset P --out DIR/<set name>` first. It writes
DIR/regions.md and DIR/regions.json (bad-2 null for a region without pixels); --images
DIR2 writes one picture per set, DIR2/regions_<set name>.png (per bin: the left view,
the ground truth, the result, the error coloured by region); --markdown FILE writes the
section: into FILE between the lines "<!-- region_report:begin -->" and
"<!-- region_report:end -->" if FILE exists (it must hold them), else as a new file.

Regions, a partition of the pixels with finite ground truth:
  parts, both cameras  a part's visible mask (mask_visib/, or bins_figures.py's rule where
                       a scene has none) and mask0nocc.png == 255;
  parts, left only     a part's pixels that the right camera does not see;
  walls                not a part, in the projector's field, and steep: the ground truth's
                       disparity changes by more than 0.25 px a pixel (per axis the smaller
                       of the two one-sided steps, so that a depth edge is not a slope);
  floor                not a part, in the projector's field, not steep (a bin's floor, the
                       table, the walls' rims);
  outside the field    not a part and outside the projector's field
                       (projector_field_split.py's rule; a scene without im0_passive.png
                       counts as lit everywhere).
A result pixel that is not finite counts as bad (the MiddEval3 SDK convention).
"""
import argparse
import json
import os
import shlex
import subprocess
import sys

import cv2
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bins_figures import pixel_classes  # noqa: E402
from make_montage import save, sheet, tile  # noqa: E402
from pfm_io import read_pfm  # noqa: E402
from projector_field_split import projector_field  # noqa: E402

STEEP = 0.25
BAD = 2.0
REGIONS = ("parts, both cameras", "parts, left only", "walls", "floor", "outside the field")
# RGB per region in the error picture: bright where bad, a dark shade where within 2 px.
COLOURS = {"parts, both cameras": (230, 30, 30), "parts, left only": (255, 0, 255),
           "walls": (255, 170, 0), "floor": (40, 120, 255), "outside the field": (0, 210, 210)}
BEGIN, END = "<!-- region_report:begin -->", "<!-- region_report:end -->"
TILE_WIDTH = 240


def fail(message):
    print(f"region_report: {message}", file=sys.stderr)
    sys.exit(1)


def slope(gt):
    """Per pixel, the disparity's change per pixel along the surface: per axis the smaller
    of the two one-sided steps (NaN where a neighbour has no ground truth), then their
    norm; 0 where no step is known."""
    g = np.where(np.isfinite(gt), gt, np.nan).astype(np.float64)
    steps = []
    for axis in (0, 1):
        forward = np.abs(np.diff(g, axis=axis))
        pad = [(0, 0), (0, 0)]
        pad[axis] = (0, 1)
        after = np.pad(forward, pad, constant_values=np.nan)
        pad[axis] = (1, 0)
        before = np.pad(forward, pad, constant_values=np.nan)
        with np.errstate(invalid="ignore"):
            steps.append(np.nan_to_num(np.fmin(after, before), nan=0.0))
    return np.hypot(*steps)


def regions(scene):
    """The ground truth and a boolean mask per region (REGIONS), a partition of its
    finite pixels."""
    gt, classes = pixel_classes(scene)
    finite, parts, nocc = classes["all"], classes["parts"], classes["nocc"]
    if os.path.isfile(os.path.join(scene, "im0_passive.png")):
        lit = projector_field(scene)
    else:
        lit = np.ones_like(finite)
    rest = finite & ~parts
    steep = slope(gt) > STEEP
    return gt, {
        "parts, both cameras": parts & nocc,
        "parts, left only": parts & ~nocc,
        "walls": rest & lit & steep,
        "floor": rest & lit & ~steep,
        "outside the field": rest & ~lit,
    }


def score(gt, disp, masks):
    """Per region, "all" and "parts" (both parts' regions): (bad-2 in %, share of the
    pixels with ground truth); and the bad-2 pixels."""
    if disp.shape != gt.shape:
        fail(f"a result is {disp.shape[1]}x{disp.shape[0]}, its ground truth "
             f"{gt.shape[1]}x{gt.shape[0]}")
    with np.errstate(invalid="ignore"):
        bad = ~(np.abs(disp - gt) <= BAD)
    finite = np.isfinite(gt)
    total = int(finite.sum())
    out = {"all": (float(bad[finite].mean() * 100), 1.0)}
    parts = masks["parts, both cameras"] | masks["parts, left only"]
    out["parts"] = (float(bad[parts].mean() * 100) if parts.any() else float("nan"),
                    float(parts.sum()) / total)
    for name in REGIONS:
        m = masks[name]
        n = int(m.sum())
        out[name] = (float(bad[m].mean() * 100) if n else float("nan"), n / total)
    return out, bad


def colour_disparity(disp, top):
    """Disparity 0..top as a JET colour image (RGB), black where not finite."""
    finite = np.isfinite(disp)
    scaled = np.clip(np.where(finite, disp, 0) / top * 255, 0, 255).astype(np.uint8)
    rgb = cv2.applyColorMap(scaled, cv2.COLORMAP_JET)[:, :, ::-1].copy()
    rgb[~finite] = 0
    return rgb


def error_by_region(masks, bad):
    """Each region's colour, bright where bad-2, a dark shade where right; black without
    ground truth."""
    out = np.zeros(bad.shape + (3,), np.uint8)
    for name, m in masks.items():
        colour = np.array(COLOURS[name], np.float64)
        out[m & bad] = colour.astype(np.uint8)
        out[m & ~bad] = (colour * 0.25).astype(np.uint8)
    return out


def picture_row(scene, gt, disp, masks, bad):
    from PIL import Image
    top = float(np.nanmax(np.where(np.isfinite(gt), gt, np.nan))) * 1.1
    left = cv2.imread(os.path.join(scene, "im0.png"))[:, :, ::-1]
    tiles = [("left view", left), ("ground truth", colour_disparity(gt, top)),
             ("result", colour_disparity(disp, top)),
             ("bad-2 by region", error_by_region(masks, bad))]
    return [(label, tile(Image.fromarray(np.ascontiguousarray(a)), width=TILE_WIDTH))
            for label, a in tiles]


def set_name(path, taken):
    parts = os.path.normpath(os.path.abspath(path)).split(os.sep)
    name = parts[-1]
    if name in taken:
        name = "_".join(parts[-2:])
    return name


def scenes_of(root, wanted):
    found = sorted(d for d in os.listdir(root)
                   if os.path.isfile(os.path.join(root, d, "disp0GT.pfm")))
    if os.path.isfile(os.path.join(root, "disp0GT.pfm")):
        fail(f"{root}: a scene, not a set of scenes (give its parent folder)")
    if wanted:
        missing = [s for s in wanted if s not in found]
        if missing:
            fail(f"{root}: no scene {missing[0]} (with disp0GT.pfm)")
        found = wanted
    if not found:
        fail(f"{root}: no scene folder with disp0GT.pfm")
    return found


def parse_sets(arguments, wanted):
    sets, taken = [], set()
    for argument in arguments:
        root, _, results = argument.partition("=")
        if not os.path.isdir(root):
            fail(f"{root}: no such folder")
        scenes = scenes_of(root, wanted)
        if results:
            for s in scenes:
                path = os.path.join(results, f"{s}_disp.pfm")
                if not os.path.isfile(path):
                    fail(f"{path}: no such file (results of {root})")
        name = set_name(root, taken)
        taken.add(name)
        sets.append({"name": name, "root": root, "results": results or None, "scenes": scenes})
    return sets


def run_eval(flexsight, root, scenes, preset, extra, out):
    command = [flexsight, "eval", root, "--out", out, "--scenes", ",".join(scenes)]
    if preset:
        command += ["--preset", preset]
    command += extra
    print("running: " + " ".join(shlex.quote(c) for c in command), file=sys.stderr)
    if subprocess.run(command, stdout=subprocess.DEVNULL).returncode != 0:
        fail(f"flexsight eval failed on {root}")


def table(rows):
    head = "| bin | all | parts | " + " | ".join(REGIONS) + " |"
    lines = [head, "|---|" + "---:|" * (len(REGIONS) + 2)]
    for label, figures in rows:
        cells = [f"{figures['all'][0]:.2f}"]
        for name in ("parts",) + REGIONS:
            bad, share = figures[name]
            cells.append("—" if share == 0 else f"{bad:.2f} ({share * 100:.1f} %)")
        bold = label == "mean"
        lines.append(f"| {'**mean**' if bold else label} | "
                     + " | ".join(f"**{c}**" if bold and c != "—" else c for c in cells) + " |")
    return "\n".join(lines)


def mean_row(per_scene):
    out = {}
    for name in ("all", "parts") + REGIONS:
        bads = [f[name][0] for f in per_scene if f[name][1] > 0]
        shares = [f[name][1] for f in per_scene]
        out[name] = (float(np.mean(bads)) if bads else float("nan"), float(np.mean(shares)))
    return out


def section(sets, command, images, markdown):
    lines = [BEGIN, "", "Written by `" + command + "`. Cells: bad-2 (%) of the region and,"
             " in brackets, its share of the pixels with ground truth; \"parts\" is both"
             " parts' regions together, the five regions after it are a partition of those"
             " pixels (the script's docstring defines them). Pictures,"
             " per bin: the left view, the ground truth, the result (the same colour scale),"
             " the pixels coloured by region, bright where bad-2 and dark where within 2 px:"
             " red parts seen by both cameras, magenta parts seen by the left one only,"
             " orange walls, blue floor, cyan outside the projector's field.", ""]
    for s in sets:
        lines += [f"**{s['name']}** (`{s['root']}`, {len(s['scenes'])} bins)", "",
                  table(s["rows"]), ""]
        if images:
            picture = os.path.relpath(s["picture"], os.path.dirname(os.path.abspath(markdown)))
            lines += [f"![bad-2 by region, {s['name']}]({picture})", ""]
    lines.append(END)
    return "\n".join(lines) + "\n"


def write_markdown(path, text):
    if os.path.exists(path):
        with open(path) as f:
            old = f.read()
        if old.count(BEGIN) != 1 or old.count(END) != 1 or old.index(BEGIN) > old.index(END):
            fail(f"{path}: exists but does not hold the lines {BEGIN} and {END} once each")
        text = old[:old.index(BEGIN)] + text.rstrip("\n") + old[old.index(END) + len(END):]
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def check_markdown_target(path):
    if path and os.path.exists(path):
        with open(path) as f:
            old = f.read()
        if old.count(BEGIN) != 1 or old.count(END) != 1:
            fail(f"{path}: exists but does not hold the lines {BEGIN} and {END} once each")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("sets", nargs="+", metavar="SET[=RESULTS]")
    p.add_argument("--out", required=True)
    p.add_argument("--flexsight", default="build/flexsight")
    p.add_argument("--preset", default="active")
    p.add_argument("--eval-option", action="append", default=[],
                   help="passed to flexsight eval (repeat; e.g. --eval-option=--window "
                        "--eval-option=25)")
    p.add_argument("--scenes", default=None)
    p.add_argument("--images", default=None)
    p.add_argument("--markdown", default=None)
    p.add_argument("--command", default=None,
                   help="the command line the Markdown names (default: this one)")
    args = p.parse_args()
    wanted = args.scenes.split(",") if args.scenes else None
    sets = parse_sets(args.sets, wanted)
    check_markdown_target(args.markdown)
    if any(s["results"] is None for s in sets) and not os.access(args.flexsight, os.X_OK):
        fail(f"{args.flexsight}: no such executable (--flexsight)")
    os.makedirs(args.out, exist_ok=True)
    if args.images:
        os.makedirs(args.images, exist_ok=True)
    report = []
    for s in sets:
        results = s["results"]
        if results is None:
            results = os.path.join(args.out, s["name"])
            run_eval(args.flexsight, s["root"], s["scenes"], args.preset, args.eval_option, results)
        rows, per_scene, pictures = [], [], []
        for scene in s["scenes"]:
            folder = os.path.join(s["root"], scene)
            gt, masks = regions(folder)
            disp = read_pfm(os.path.join(results, f"{scene}_disp.pfm"))
            figures, bad = score(gt, disp, masks)
            rows.append((scene, figures))
            per_scene.append(figures)
            if args.images:
                pictures.append((scene, picture_row(folder, gt, disp, masks, bad)))
        if len(rows) > 1:
            rows.append(("mean", mean_row(per_scene)))
        s["rows"] = rows
        if args.images:
            s["picture"] = os.path.join(args.images, f"regions_{s['name']}.png")
            # 256 colours: the dots' noise in the left view would make most of a full-colour
            # PNG's bytes; the octree keeps the few colours of the maps exact.
            from PIL import Image
            picture = sheet(pictures).quantize(colors=256, method=Image.Quantize.FASTOCTREE,
                                               dither=Image.Dither.NONE)
            save(picture, s["picture"], optimize=True)
        report.append({"set": s["name"], "root": s["root"], "results": results,
                       "scenes": {label: {k: {"bad2": v[0] if np.isfinite(v[0]) else None,
                                              "share": v[1]} for k, v in f.items()}
                                  for label, f in rows}})
        print(f"## {s['name']}\n\n{table(rows)}\n")
    command = args.command or "scripts/stereo/region_report.py " + " ".join(
        shlex.quote(a) for a in sys.argv[1:])
    markdown = args.markdown or os.path.join(args.out, "regions.md")
    text = section(sets, command, args.images, markdown)
    with open(os.path.join(args.out, "regions.md"), "w") as f:
        f.write(text)
    with open(os.path.join(args.out, "regions.json"), "w") as f:
        json.dump(report, f, indent=1, allow_nan=False)
    if args.markdown:
        write_markdown(args.markdown, text)


if __name__ == "__main__":
    main()

"""The figures of the benchmark report (make_report.py): runtime against bad 2, the
sparsification curves (matplotlib) and the montages of disparity and error maps (PIL)."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image, ImageDraw  # noqa: E402

from report_tables import (LABEL, METHODS, averages, methods_with_confidence,  # noqa: E402
                           scenes_of)

# Same bytes as their OpenCL run (the byte tests prove it): one picture is enough.
NOT_IN_MONTAGE = {"ppms-fast-reference"}


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

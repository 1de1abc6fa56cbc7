#!/usr/bin/env python3
"""Class-agnostic recall at IoU 0.5 by part size, whole image against tiles, from the
report.json files scripts/detect/eval_tiles.sh leaves (docs/images/detect_recall_by_size.png).

Usage: plot_tile_recall.py OUT.png TITLE=RUN_DIR:TILE [TITLE=RUN_DIR:TILE ...]
Each panel: the whole image (RUN_DIR/tile_0) and tiles (RUN_DIR/tile_TILE); bars at any
score (light) and from the report's recall score (dark).
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def figures(report_path):
    with open(report_path) as f:
        report = json.load(f)
    sizes = [s for s in report["by_size"] if s["class_agnostic"]["ground_truth"] > 0]
    return ([s["label"] for s in sizes], [s["class_agnostic"] for s in sizes],
            report["class_agnostic"]["recall_score"])


def main():
    out, panels = sys.argv[1], sys.argv[2:]
    fig, axes = plt.subplots(1, len(panels), figsize=(4.2 * len(panels), 3.4), squeeze=False)
    for ax, panel in zip(axes[0], panels):
        title, spec = panel.rsplit("=", 1)
        run, tile = spec.rsplit(":", 1)
        labels, whole, score = figures(f"{run}/tile_0/report.json")
        _, tiled, _ = figures(f"{run}/tile_{tile}/report.json")
        x = range(len(labels))
        for offset, data, name, colour in ((-0.2, whole, "whole image", "tab:grey"),
                                           (0.2, tiled, f"tiles {tile} px", "tab:blue")):
            ax.bar([i + offset for i in x], [d["recall_any"] for d in data], 0.38, color=colour, alpha=0.35)
            ax.bar([i + offset for i in x], [d["recall_at_score"] for d in data], 0.38, color=colour,
                   label=f"{name} (dark: score >= {score:g})")
        ax.set_xticks(list(x))
        ax.set_xticklabels([f"{l}\n({d['ground_truth']})" for l, d in zip(labels, whole)])
        ax.set_ylim(0, 1.05)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel("part size, sqrt(box area) px (parts)", fontsize=8)
        ax.grid(axis="y", alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
    axes[0][0].set_ylabel("class-agnostic recall, IoU 0.5")
    fig.tight_layout()
    fig.savefig(out, dpi=80)


if __name__ == "__main__":
    main()

"""The figure of docs/detect-training.md "Bins in the training data": the training and
validation loss of each mix's fine-tuning against images trained (left; each mix validates on
its own images), and per-class mAP@0.5 and class-agnostic AP@0.5 of each model on each set
(right), from detect.mix_eval's reports.

    python3 -m detect.plot_mixes OUT.png RUN_DIR MODELS SETS     # from scripts/
    python3 -m detect.plot_mixes ../docs/images/detect_bin_mix.png ../out/bintrain \
        shipped,full,full_bins,bins bins_dev,bins_test,active_bins,synth300
"""
from __future__ import annotations

import csv
import json
import sys
from pathlib import Path


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 1
    out, run = Path(argv[0]), Path(argv[1])
    models, sets = argv[2].split(","), argv[3].split(",")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4), gridspec_kw={"width_ratios": [1, 1.6]})
    for k, m in enumerate(models):
        log = run / m / "log.csv"
        if not log.is_file():
            continue
        rows = list(csv.DictReader(log.open()))
        summary = json.loads((run / m / "summary.json").read_text())
        per_epoch = summary["train_images"]
        budget = int(summary["settings"].get("max_images", "0")) or 1 << 62  # --max-images stops within an epoch
        x = [min(int(r["epoch"]) * per_epoch, budget) for r in rows]
        ax.plot(x, [float(r["train_loss"]) for r in rows], "o-", color="C%d" % k, label=m + " train")
        ax.plot(x, [float(r["val_loss"]) for r in rows], "s--", color="C%d" % k, label=m + " validation")
    ax.set_xlabel("images trained")
    ax.set_ylabel("SSD loss")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    width = 0.8 / len(models)
    for k, m in enumerate(models):
        for j, s in enumerate(sets):
            r = json.loads((run / "eval" / ("%s_%s" % (m, s)) / "report.json").read_text())
            x = j + (k - (len(models) - 1) / 2) * width
            bx.bar(x, r["class_agnostic"]["ap50"], width, color="C%d" % k, alpha=0.35)
            bx.bar(x, r["map50"], width, color="C%d" % k, label=m if j == 0 else None)
    bx.set_xticks(range(len(sets)))
    bx.set_xticklabels(sets)
    bx.set_ylabel("mAP@0.5 (dark), class-agnostic AP@0.5 (light)")
    bx.set_ylim(0, 1)
    bx.grid(True, axis="y", alpha=0.3)
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=80)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

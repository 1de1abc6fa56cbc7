"""eval-det of several detectors on several data sets and one Markdown table of the figures
docs/detect-training.md compares training mixes by: per-class mAP@0.5, class-agnostic AP@0.5
and COCO AP, class-agnostic recall at IoU 0.5 from score 0.3 and at any score, and recall at
any score by part size (sqrt of the box area).

    python3 -m detect.mix_eval --out DIR --model NAME=M.onnx ... --set NAME=DATASET[@TILE] ...
                               [--min-visible 0.5] [--flexsight build/flexsight]   # from scripts/

Each (model, set) runs `flexsight eval-det DATASET --model M.onnx --tile TILE --out
DIR/NAME_SET` once (--min-visible for BOP folders only); a report.json already there is reused, so sets can be added later.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path


def pair(text: str):
    name, sep, value = text.partition("=")
    if not sep or not name or not value:
        raise argparse.ArgumentTypeError("%s: not NAME=VALUE" % text)
    return name, value


def run(args, model: str, onnx: str, set_name: str, dataset: str) -> dict:
    path, _, tile = dataset.partition("@")
    out = args.out / ("%s_%s" % (model, set_name))
    if not (out / "report.json").is_file():
        bop = not (Path(path) / "coco_instances.json").is_file() and not path.endswith(".json")
        visible = ["--min-visible", str(args.min_visible)] if bop else []  # COCO sets have none
        subprocess.run([str(args.flexsight), "eval-det", path, "--model", onnx, "--tile", tile or "0",
                        *visible, "--out", str(out), "--overwrite", "--quiet", "--montage", "0",
                        "--threads", str(args.threads)], check=True, stdout=subprocess.DEVNULL)
    return json.loads((out / "report.json").read_text())


def row(model: str, set_name: str, r: dict) -> str:
    f = lambda v: "-" if v is None else "%.3f" % v  # noqa: E731
    a = r["class_agnostic"]
    sizes = [s["class_agnostic"] for s in r["by_size"] if s["label"] != "<32"]
    return "| %s | %s | %s | %s | %s | %s / %s | %s |" % (
        set_name, model, f(r["map50"]), f(a["ap50"]), f(a["coco_ap"]), f(a["recall_at_score"]),
        f(a["recall_any"]), " / ".join(f(s["recall_any"]) for s in sizes))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--model", type=pair, action="append", required=True, help="NAME=M.onnx")
    ap.add_argument("--set", type=pair, action="append", required=True, help="NAME=DATASET[@TILE]")
    ap.add_argument("--min-visible", type=float, default=0.5)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--flexsight", type=Path, default=Path(__file__).resolve().parents[2] / "build" / "flexsight")
    args = ap.parse_args(argv)
    for _, onnx in args.model:
        if not Path(onnx).is_file():
            print("error: --model %s: missing" % onnx, file=sys.stderr)
            return 1
    print("| set | model | mAP@0.5 | class-agnostic AP@0.5 | class-agnostic COCO AP | recall >= 0.3 / any"
          " | recall any: 32-64 / 64-128 / >= 128 px |")
    print("|---|---|---:|---:|---:|---:|---:|")
    for set_name, dataset in args.set:
        for model, onnx in args.model:
            print(row(model, set_name, run(args, model, onnx, set_name, dataset)), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

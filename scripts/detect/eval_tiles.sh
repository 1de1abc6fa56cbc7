#!/usr/bin/env bash
# eval-det on one data set, the whole image and each tile size given, and a Markdown table of
# the figures docs/detect.md ("Small parts: tiles and part size") quotes: per-class mAP@0.5,
# class-agnostic AP@0.5, and class-agnostic recall at IoU 0.5 by part size (score >= 0.3 and
# any score).
#
#   scripts/detect/eval_tiles.sh DATASET OUT_DIR "0 256 320" [eval-det options]
#
# FLEXSIGHT (default build/flexsight) is the binary; each run's report goes to OUT_DIR/tile_N.
set -euo pipefail
cd "$(dirname "$0")/../.."
dataset=$1 out=$2 tiles=$3
shift 3
flexsight=${FLEXSIGHT:-build/flexsight}
mkdir -p "$out"
for tile in $tiles; do
  start=$(date +%s.%N)
  "$flexsight" eval-det "$dataset" --tile "$tile" --out "$out/tile_$tile" --overwrite --quiet --montage 0 "$@" \
    > "$out/tile_$tile.log" 2>&1
  echo "$(echo "$(date +%s.%N) - $start" | bc)" > "$out/tile_$tile.seconds"
done
python3 - "$out" $tiles <<'PY'
import json, sys
out, tiles = sys.argv[1], sys.argv[2:]
f = lambda v: "-" if v is None else f"{v:.3f}"
print("| tiles | mAP@0.5 | class-agnostic AP@0.5 | recall >= 0.3 / any score: all | <32 px | 32-64 px | 64-128 px | >=128 px | seconds |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for tile in tiles:
    r = json.load(open(f"{out}/tile_{tile}/report.json"))
    a = r["class_agnostic"]
    cells = [f"{f(a['recall_at_score'])} / {f(a['recall_any'])} ({a['ground_truth']})"]
    for s in r["by_size"]:
        c = s["class_agnostic"]
        cells.append(f"{f(c['recall_at_score'])} / {f(c['recall_any'])} ({c['ground_truth']})" if c["ground_truth"] else "-")
    secs = float(open(f"{out}/tile_{tile}.seconds").read())
    name = "whole image" if tile == "0" else f"{tile} px"
    print(f"| {name} | {f(r['map50'])} | {f(a['ap50'])} | " + " | ".join(cells) + f" | {secs:.0f} |")
PY

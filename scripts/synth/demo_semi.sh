#!/usr/bin/env bash
# The semi-synthetic pipeline end to end on what this repository has: patches cut from
# renders made with other settings than the full-synthetic defaults (one large part per
# image, one light plus a camera light, hard shadows, little noise, no flips), then
# pasted on the background photographs. The method wants real photographs of the parts
# (docs/synth.md, "Semi-synthetic images"); point `synth patches` at them when you have
# them.
#   scripts/synth/demo_semi.sh OUT_DIR [COUNT]
# writes OUT_DIR/patch_source, OUT_DIR/patches and OUT_DIR/semi (COUNT images, default 100).
set -euo pipefail
out="${1:?usage: demo_semi.sh OUT_DIR [COUNT]}"
count="${2:-100}"
flexsight="${FLEXSIGHT:-$(dirname "$0")/../../build/flexsight}"
mkdir -p "$out"
"$flexsight" synth full --count 200 --size 400x400 --max-parts 1 --min-size 0.4 --max-size 0.8 \
  --camera-light 1 --max-lights 1 --soft-shadows 0 --max-noise 2 --max-blur 0.5 \
  --hflip 0 --vflip 0 --max-rotation 0 --no-depth --rgb png --seed 1000 \
  -o "$out/patch_source" --overwrite
"$flexsight" synth patches "$out/patch_source" -o "$out/patches" --overwrite
"$flexsight" synth semi --patches "$out/patches" --count "$count" -o "$out/semi" --overwrite

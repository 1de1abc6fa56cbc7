#!/usr/bin/env bash
# The matcher's output bytes, as SHA-256 sums: the disparity, the planes and the
# confidence of both paths (reference, OpenCL) with the defaults and with --preset fast,
# on the committed fixture (tests/data/TeddyH) and two MiddEval3 Q scenes. A change
# that must not move a byte (a refactoring, a new module) is checked with
#   scripts/stereo/output_hashes.sh --check      (compares with the recorded sums)
#   scripts/stereo/output_hashes.sh --record     (rewrites them, after a deliberate change)
# The recorded sums are tests/data/stereo_output_hashes.sha256. MiddEval3 comes from
# MIDDEVAL3_DIR (default ../shared/datasets/MiddEval3-trainingQ); a missing scene fails.
set -euo pipefail
cd "$(dirname "$0")/../.."

mode=${1:---check}
case "$mode" in --check|--record) ;; *) echo "usage: $0 [--check|--record]" >&2; exit 2 ;; esac
binary=${FLEXSIGHT_BINARY:-build/flexsight}
middeval=${MIDDEVAL3_DIR:-../shared/datasets/MiddEval3-trainingQ}
recorded=tests/data/stereo_output_hashes.sha256
[ -x "$binary" ] || { echo "$0: $binary is not built (scripts/setup.sh builds it)" >&2; exit 1; }

scenes=(tests/data/TeddyH "$middeval/Teddy" "$middeval/Motorcycle")
for scene in "${scenes[@]}"; do
  [ -f "$scene/im0.png" ] || { echo "$0: scene $scene is missing (im0.png)" >&2; exit 1; }
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for scene in "${scenes[@]}"; do
  name=$(basename "$scene")
  for preset in default fast; do
    preset_option=()
    [ "$preset" = fast ] && preset_option=(--preset fast)
    for device in reference opencl; do
      run="$name.$preset.$device"
      echo "$0: $run" >&2
      "$binary" stereo "$scene" --quiet --seed 1 --device "$device" "${preset_option[@]}" \
        -o "$work/$run.disparity.pfm" --planes "$work/$run.planes.pfm" \
        --conf "$work/$run.confidence.pfm" > /dev/null
    done
  done
done

(cd "$work" && sha256sum -- *.pfm) > "$work/sums"
if [ "$mode" = --record ]; then
  cp "$work/sums" "$recorded"
  echo "$0: recorded $(wc -l < "$recorded") sums in $recorded"
else
  if diff -u "$recorded" "$work/sums"; then
    echo "$0: all $(wc -l < "$recorded") outputs have their recorded bytes"
  else
    echo "$0: outputs differ from $recorded (above)" >&2
    exit 1
  fi
fi

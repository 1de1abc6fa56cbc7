#!/usr/bin/env bash
# The bytes of the newer commands' outputs on small fixed inputs, timings taken out
# (normalised_sums.py): synth full, synth bin, detect, pose-templates, pose (dataset
# form, ground-truth boxes), pick and eval-pick. A change that must not move a byte (a
# refactoring) is checked with
#   scripts/check/command_outputs.sh --check     (compares with the recorded sums)
#   scripts/check/command_outputs.sh --record    (rewrites them, after a deliberate change)
# The recorded sums are tests/data/command_output_sums.sha256; the stereo outputs have
# their own check (scripts/stereo/output_hashes.sh). The CAD models and backgrounds come
# from FLEXSIGHT_DETECTION_DATA (default ../shared/detection); a missing one fails.
set -euo pipefail
cd "$(dirname "$0")/../.."

mode=${1:---check}
case "$mode" in --check|--record) ;; *) echo "usage: $0 [--check|--record]" >&2; exit 2 ;; esac
binary=${FLEXSIGHT_BINARY:-build/flexsight}
data=${FLEXSIGHT_DETECTION_DATA:-../shared/detection}
recorded=tests/data/command_output_sums.sha256
[ -x "$binary" ] || { echo "$0: $binary is not built (scripts/setup.sh builds it)" >&2; exit 1; }
for folder in "$data/cad/tless" "$data/backgrounds"; do
  [ -d "$folder" ] || { echo "$0: $folder is missing" >&2; exit 1; }
done

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run() {
  echo "$0: flexsight $1 $2" >&2
  "$binary" "$@" > /dev/null 2> "$work/last.err" || { cat "$work/last.err" >&2; exit 1; }
}
cad=(--cad "$data/cad/tless")
out=$work/out
mkdir -p "$out"/{detect,templates,pick}

run synth full --count 4 --size 200x200 --seed 5 --threads 2 "${cad[@]}" \
  --backgrounds "$data/backgrounds" -o "$out/full"
run synth bin --count 2 --seed 11 --size 480x360 --parts 6..6 "${cad[@]}" -o "$out/bins"
run detect "$out/full" --threads 2 -o "$out/detect/detections.json" --png "$out/detect/boxes.png"
run pose-templates "$data/cad/tless" --views 40 --threads 2 -o "$out/templates/parts.tpl"
pose_inputs=(--templates "$out/templates/parts.tpl" "${cad[@]}" --threads 2)
run pose "$out/bins/bin000" --gt-boxes "${pose_inputs[@]}" --out "$out/pose"
run pick "$out/bins/bin000" "${pose_inputs[@]}" -o "$out/pick/picks.json" --png "$out/pick/picks.png"
run eval-pick "$out/bins" --pattern-only "${pose_inputs[@]}" --out "$out/eval-pick"

python3 scripts/check/normalised_sums.py "$out" > "$work/sums"
if [ "$mode" = --record ]; then
  cp "$work/sums" "$recorded"
  echo "$0: recorded $(wc -l < "$recorded") sums in $recorded"
elif diff -u "$recorded" "$work/sums"; then
  echo "$0: all $(wc -l < "$recorded") outputs have their recorded bytes"
else
  echo "$0: outputs differ from $recorded (above)" >&2
  exit 1
fi

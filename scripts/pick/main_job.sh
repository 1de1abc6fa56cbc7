#!/usr/bin/env bash
# The main job (scripts/run.sh): a pick on a simulated bin, with nothing from outside the
# repository. Makes our own part (demo_part.py: a bracket, given object id 5 because
# known-part mode needs an id the shipped detector has a class for; docs/quickstart.md),
# the edge templates of that part alone, one bin of it (synth bin), then `flexsight pick
# --parts 5` on the bin, and prints the first pick and the time per stage.
#
#   scripts/pick/main_job.sh [--out DIR] [--size WxH] [--seed S] [--flexsight BIN] [PICK_OPTION...]
#
# Writes DIR/PICKS.json, DIR/pick.png (the left view, the parts' outlines at their poses,
# the first pick green) and DIR/pick.md (pick's table); its inputs under DIR/pick_job/.
# Defaults: out, 1280x960 (the product's camera), seed 1, build/flexsight. Every other
# argument goes to `flexsight pick` (e.g. --stereo-downscale 2, --threads 1).
set -euo pipefail
cd "$(dirname "$0")/../.."

out=out size=1280x960 seed=1 flexsight=build/flexsight
pick_options=()
while [ $# -gt 0 ]; do
  case "$1" in
    --out|--size|--seed|--flexsight)
      [ $# -ge 2 ] || { echo "$0: option $1 needs a value" >&2; exit 1; }
      case "$1" in --out) out=$2 ;; --size) size=$2 ;; --seed) seed=$2 ;; --flexsight) flexsight=$2 ;; esac
      shift 2 ;;
    *) pick_options+=("$1"); shift ;;
  esac
done
[ -x "$flexsight" ] || { echo "$0: $flexsight is not built (scripts/setup.sh builds it)" >&2; exit 1; }

part=5
job=$out/pick_job
mkdir -p "$job/cad"
seconds() { /usr/bin/python3 -c 'import sys, time; print(f"{time.time() - float(sys.argv[1]):.1f}")' "$1"; }

/usr/bin/python3 scripts/pick/demo_part.py "$job/cad/obj_0$part.stl"
# The bin first: a size it refuses stops the job before the templates are made.
start=$(date +%s.%N)
"$flexsight" synth bin --count 1 --seed "$seed" --size "$size" --parts "$part" --cad "$job/cad" \
  -o "$job/bins" --overwrite > /dev/null
bin_s=$(seconds "$start")

start=$(date +%s.%N)
"$flexsight" pose-templates "$job/cad" -o "$job/parts.tpl" > /dev/null
templates_s=$(seconds "$start")

start=$(date +%s.%N)
"$flexsight" pick "$job/bins/bin000" --templates "$job/parts.tpl" --cad "$job/cad" --parts "$part" \
  -o "$out/PICKS.json" --png "$out/pick.png" "${pick_options[@]}" > "$out/pick.md"
pick_s=$(seconds "$start")

echo "main job: bin ${size} ${bin_s} s, templates of the part ${templates_s} s, pick ${pick_s} s (process)"
/usr/bin/python3 scripts/pick/first_pick.py "$out/PICKS.json"
echo "wrote $out/PICKS.json, $out/pick.png (the picture), $out/pick.md (every pick)"

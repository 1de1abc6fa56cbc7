#!/usr/bin/env bash
# Fine-tunes the shipped detector on mixes of full-synthetic images and bin views (whole and
# in pick's tiles), one feature cache for all mixes, and scores each on the development bins.
#
#   scripts/detect/train_bin_mix.sh RUN_DIR [MIX ...]
#
# MIX is NAME=SOURCES (comma-separated sources of the mixed set: full, bins500, bins501);
# default: full_bins=full,bins500,bins501 bins=bins500,bins501 full=full. Every mix trains on
# the same number of images (STEPS, default 3000: detect.train --max-images, the learning rate's
# cosine ending there), seed 1, from INIT (default: the detector shipped before bins were in its
# data, models/tless-ssd/model.onnx of commit 830ea96, taken from git). Data (made when missing,
# under RUN_DIR): 4000 `synth full` images at 300x300, seed 21, the 250 training backgrounds;
# bins of `synth bin` seeds 500 (16 bins, defaults), 501 (16, --vary all) and 502 (8, --vary
# all --pile dense), never used by an evaluation set, cut by detect.bin_tiles into the whole
# passive left view and tiles of 256 and 336 px. PYTHON (default /usr/bin/python3) trains.
# The mixes are scored on DEV_BINS (default /work/data/bins_dev, 256-px tiles) and on 300
# full-synthetic test images (seed 2, the held-out backgrounds); the table goes to
# RUN_DIR/dev_table.md.
set -euo pipefail
cd "$(dirname "$0")/../.."
run=$1
shift
mixes=("$@")
[ ${#mixes[@]} -gt 0 ] || mixes=(full_bins=full,bins500,bins501 bins=bins500,bins501 full=full)
python=${PYTHON:-/usr/bin/python3}
steps=${STEPS:-3000}
backgrounds=${FLEXSIGHT_DETECTION_DATA:-../shared/detection}/backgrounds
mkdir -p "$run"
run=$(cd "$run" && pwd)

scripts/detect/split_backgrounds.sh "$backgrounds" "$run/backgrounds"
[ -f "$run/full21/coco_instances.json" ] || build/flexsight synth full --count 4000 --seed 21 \
  --no-depth --no-masks --backgrounds "$run/backgrounds/train" -o "$run/full21"
[ -d "$run/bins500" ] || build/flexsight synth bin --count 16 --seed 500 -o "$run/bins500"
[ -d "$run/bins501" ] || build/flexsight synth bin --count 16 --seed 501 --vary all -o "$run/bins501"
[ -d "$run/bins502" ] || build/flexsight synth bin --count 8 --seed 502 --vary all --pile dense \
  -o "$run/bins502"
[ -f "$run/test300_seed2/coco_instances.json" ] || build/flexsight synth full --count 300 --seed 2 \
  --no-depth --no-masks --backgrounds "$run/backgrounds/test" -o "$run/test300_seed2"
init=${INIT:-$run/init.onnx}
[ -n "${INIT:-}" ] || [ -f "$init" ] || git show 830ea96:models/tless-ssd/model.onnx > "$init"
init=$(cd "$(dirname "$init")" && pwd)/$(basename "$init")
cd scripts
[ -d "$run/tiles500" ] || "$python" -m detect.bin_tiles "$run/bins500" -o "$run/tiles500" --tile 256 336
[ -d "$run/tiles501" ] || "$python" -m detect.bin_tiles "$run/bins501" "$run/bins502" \
  -o "$run/tiles501" --tile 256 336
[ -d "$run/mix" ] || "$python" -m detect.mix_sets -o "$run/mix" full="$run/full21" \
  bins500="$run/tiles500" bins501="$run/tiles501"

models=()
for mix in "${mixes[@]}"; do
  name=${mix%%=*} sources=${mix#*=}
  if [ ! -f "$run/$name/model.onnx" ]; then
    "$python" -m detect.train --data "$run/mix" --cache "$run/features" --out "$run/$name" \
      --sources "$sources" --init-onnx "$init" --backbone oidv4 \
      --tune-from 13 --backbone-lr-factor 0.3 --lr 3e-4 --max-images "$steps" --ap-images 100 --seed 1
  fi
  models+=(--model "$name=$run/$name/model.onnx")
done
"$python" -m detect.mix_eval --out "$run/eval" --model start="$init" "${models[@]}" \
  --set bins_dev="${DEV_BINS:-/work/data/bins_dev}@256" --set synth300="$run/test300_seed2@0" \
  | tee "$run/dev_table.md"

#!/usr/bin/env bash
# Packs .device/ (git-ignored) for a bare GPU machine that has no apt, no OpenCV and no
# copy of ../shared: the device check (bench/stereo/device_check.cpp), every library it loads
# except glibc's, and the quarter-resolution MiddEval3 pairs as gzipped binary PPM with
# their ndisp. scripts/stereo/device_run.sh runs it there; about 45 MiB in all, under the
# device tool's 64 MiB for what travels.
# usage: scripts/stereo/device_bundle.sh [MIDDEVAL3_TRAININGQ_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
data=${1:-${FLEXSIGHT_DATASETS:-../shared/datasets}/MiddEval3-trainingQ}
[ -d "$data" ] || { echo "device_bundle: no MiddEval3 folder at $data" >&2; exit 1; }
[ -x build/bench/flexsight_device_check ] || scripts/setup.sh
rm -rf .device
mkdir -p .device/bin .device/lib .device/scenes
cp build/bench/flexsight_device_check .device/bin/
# glibc (libc, libm, the loader) stays: it must match the machine's own kernel interface.
ldd build/bench/flexsight_device_check | awk '$3 ~ /^\// {print $3}' |
  grep -v -E '/(libc|libm|libpthread|libdl|librt)\.so' |
  while read -r lib; do cp -L "$lib" .device/lib/; done
manifest=.device/scenes/manifest.txt
: > "$manifest"
for scene in "$data"/*/; do
  name=$(basename "$scene")
  [ -f "$scene/im0.png" ] && [ -f "$scene/calib.txt" ] || continue
  ndisp=$(sed -n 's/^ndisp=//p' "$scene/calib.txt")
  /usr/bin/python3 - "$scene" ".device/scenes/$name" <<'PY'
import sys
from PIL import Image
for view in ("0", "1"):
    Image.open(f"{sys.argv[1]}/im{view}.png").convert("RGB").save(f"{sys.argv[2]}_{view}.ppm")
PY
  gzip -f -6 ".device/scenes/${name}_0.ppm" ".device/scenes/${name}_1.ppm"
  echo "$name ${name}_0.ppm ${name}_1.ppm $ndisp" >> "$manifest"
done
echo "device_bundle: $(wc -l < "$manifest") scenes, $(du -sh .device | cut -f1) in .device/"

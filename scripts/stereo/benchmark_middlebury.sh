#!/usr/bin/env bash
# The README's benchmark tables, in one run, with default parameters:
#   1. PPMS, reference path, every scene of a MiddEval3 quarter-resolution folder;
#   2. flat PMS, reference path, on a subset (it is ~3x slower), for the PPMS/PMS ratio;
#   3. PPMS, OpenCL path (the first OpenCL device: PoCL on a machine without a GPU),
#      every scene, for the OpenCL/reference ratio and the bit-exactness check.
# Reports, colored disparities and error maps go to docs/benchmark/<run>/.
# usage: scripts/stereo/benchmark_middlebury.sh [MIDDEVAL3_TRAININGQ_DIR] [PMS_SCENES]
set -euo pipefail
cd "$(dirname "$0")/../.."
data=${1:-${FLEXSIGHT_DATASETS:-../shared/datasets}/MiddEval3-trainingQ}
pms_scenes=${2:-ArtL,Teddy,Motorcycle}
[ -x build/flexsight ] || scripts/setup.sh
out=docs/benchmark
mkdir -p "$out"
build/flexsight eval "$data" --method ppms --device reference --out "$out/ppms-reference"
build/flexsight eval "$data" --method pms --device reference --scenes "$pms_scenes" \
  --out "$out/pms-reference"
build/flexsight eval "$data" --method ppms --device opencl --out "$out/ppms-opencl"
# The OpenCL result must equal the reference byte for byte, scene by scene.
for reference in "$out"/ppms-reference/*_disp.pfm; do
  cmp "$reference" "$out/ppms-opencl/$(basename "$reference")"
done
echo "OpenCL and reference disparities are identical for every scene"
# Pictures: the PMS subset side by side with PPMS, and three scenes where PPMS fails most.
scripts/stereo/make_montage.py "$data" "$out/montage.jpg" "$pms_scenes" \
  PPMS="$out/ppms-reference" PMS="$out/pms-reference"
scripts/stereo/make_montage.py "$data" "$out/montage-hard.jpg" Adirondack,PianoL,Shelves \
  PPMS="$out/ppms-reference"
# The per-scene files were needed for the comparison and the montages; the reports and
# montages are what is kept (the per-scene pictures would add 20 MB to the repository).
# Only this script's run folders: docs/benchmark/report/ keeps its plot.
rm -f "$out"/{ppms-reference,pms-reference,ppms-opencl}/*.{pfm,png}

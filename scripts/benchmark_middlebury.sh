#!/usr/bin/env bash
# The README's benchmark table: PPMS on every scene of a MiddEval3 quarter-resolution
# folder, flat PMS on a subset (it is ~3x slower), both with default parameters, in one
# run. Reports, colored disparities and error maps go to docs/benchmark/{ppms,pms}/.
# usage: scripts/benchmark_middlebury.sh [MIDDEVAL3_TRAININGQ_DIR] [PMS_SCENES]
set -euo pipefail
cd "$(dirname "$0")/.."
data=${1:-${FLEXSIGHT_DATASETS:-../shared/datasets}/MiddEval3-trainingQ}
pms_scenes=${2:-ArtL,Teddy,Motorcycle}
[ -x build/flexsight ] || scripts/setup.sh
mkdir -p docs/benchmark
build/flexsight eval "$data" --method ppms --out docs/benchmark/ppms | tee docs/benchmark/ppms.txt
build/flexsight eval "$data" --method pms --scenes "$pms_scenes" --out docs/benchmark/pms | tee docs/benchmark/pms.txt
# Drop the per-scene PFMs: the pictures and the reports are what people read.
rm -f docs/benchmark/*/*.pfm

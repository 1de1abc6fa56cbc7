#!/usr/bin/env bash
# The README's benchmark table: PPMS on every scene of a MiddEval3 quarter-resolution
# folder, then PPMS and flat PMS on a subset (PMS is ~3x slower) for their time ratio,
# all with default parameters, in one run. Reports, colored disparities and error maps
# go to docs/benchmark/{ppms,ppms-subset,pms-subset}/.
# usage: scripts/benchmark_middlebury.sh [MIDDEVAL3_TRAININGQ_DIR] [PMS_SCENES]
set -euo pipefail
cd "$(dirname "$0")/.."
data=${1:-${FLEXSIGHT_DATASETS:-../shared/datasets}/MiddEval3-trainingQ}
pms_scenes=${2:-ArtL,Teddy,Motorcycle}
[ -x build/flexsight ] || scripts/setup.sh
mkdir -p docs/benchmark
if [ "${SKIP_FULL:-0}" != 1 ]; then
  build/flexsight eval "$data" --method ppms --out docs/benchmark/ppms
fi
build/flexsight eval "$data" --method ppms --scenes "$pms_scenes" --out docs/benchmark/ppms-subset
build/flexsight eval "$data" --method pms --scenes "$pms_scenes" --out docs/benchmark/pms-subset
# Drop the per-scene PFMs: the pictures and the reports are what people read.
rm -f docs/benchmark/*/*.pfm

#!/usr/bin/env bash
# The benchmark report of docs/benchmark/report/: our matchers and OpenCV's, in one run on
# this machine, over a MiddEval3 quarter-resolution folder and a KITTI 2012 folder.
#
# usage: scripts/stereo/benchmark_report.sh MIDDEVAL3_Q_ROOT [KITTI_ROOT] [OUT_DIR]
#   e.g. scripts/stereo/benchmark_report.sh ../shared/datasets/MiddEval3-trainingQ ../shared/datasets/KITTI2012
# Environment: FLEXSIGHT_REPEAT (runs per scene for the timed methods, default 3; the
# median is reported), FLEXSIGHT_REFERENCE_SCENES (scenes for the slow reference path,
# default ArtL,Teddy,Motorcycle), FLEXSIGHT_MONTAGE_SCENES (default Teddy,Motorcycle,PianoL).
set -euo pipefail
cd "$(dirname "$0")/../.."
[ $# -ge 1 ] || { sed -n 2,11p "$0"; exit 1; }
middlebury=$1
kitti=${2:-}
out=${3:-docs/benchmark/report}
repeat=${FLEXSIGHT_REPEAT:-3}
reference_scenes=${FLEXSIGHT_REFERENCE_SCENES:-ArtL,Teddy,Motorcycle}
montage_scenes=${FLEXSIGHT_MONTAGE_SCENES:-Teddy,Motorcycle,PianoL}
runs=out/report-runs  # per-scene PFM/PNG of every method: large, not committed
flexsight=build/flexsight

step() { echo "[$(date +%H:%M:%S)] $*" >&2; }
[ -d "$middlebury" ] || { echo "benchmark_report: $middlebury: no such folder" >&2; exit 1; }
[ -z "$kitti" ] || [ -d "$kitti" ] || { echo "benchmark_report: $kitti: no such folder" >&2; exit 1; }
step "building"
cmake --build build -j"$(nproc)" >/dev/null
commit="\`$(git rev-parse --short HEAD)\`"
# Code changes only: docs/ holds benchmark outputs, which the other benchmark script may
# have just rewritten.
git diff --quiet HEAD -- . ":(exclude)docs" 2>/dev/null || commit="$commit with uncommitted changes"
rm -rf "$runs"
mkdir -p "$runs" "$out"

# label | flexsight eval arguments. The same parameters for every PatchMatch run.
methods=(
  "ppms-opencl|--device opencl --repeat $repeat"
  "pms-opencl|--device opencl --method pms"
  "ppms-reference|--device reference --scenes REFERENCE"
  "pms-reference|--device reference --method pms --scenes REFERENCE"
  "ppms-fast-opencl|--device opencl --preset fast --repeat $repeat"
  "ppms-fast-reference|--device reference --preset fast --scenes REFERENCE"
  "opencv-sgbm|--method sgbm --repeat $repeat"
  "opencv-bm|--method bm --repeat $repeat"
)

run_dataset() {  # name root reference_scenes
  local name=$1 root=$2 subset=$3 entry label arguments
  for entry in "${methods[@]}"; do
    label=${entry%%|*}
    arguments=${entry#*|}
    arguments=${arguments/REFERENCE/$subset}
    step "$name: $label ($arguments)"
    # shellcheck disable=SC2086  # arguments are words on purpose
    "$flexsight" eval "$root" --out "$runs/$name-$label" $arguments 2>&1 >/dev/null |
      grep --line-buffered -E '^\[[0-9]+/[0-9]+\] [^:]+: [0-9.]+ s' | sed -u -e 's/ on the OpenCL path on .*/ (OpenCL)/' -e 's/^/    /' >&2 || true
    [ -f "$runs/$name-$label/report.json" ] || { echo "benchmark_report: $label failed on $name" >&2; exit 1; }
  done
}

run_dataset middlebury "$middlebury" "$reference_scenes"
if [ -n "$kitti" ]; then
  # One KITTI pair: the reference path runs on it too.
  run_dataset kitti "$kitti" "$(basename "$(ls "$kitti"/training/colored_0/*_10.png | head -1)" .png)"
fi

step "writing $out"
/usr/bin/python3 scripts/stereo/make_report.py --runs "$runs" --out "$out" --middlebury "$middlebury" \
  ${kitti:+--kitti "$kitti"} --montage "$montage_scenes" --repeat "$repeat" \
  --reference-scenes "$reference_scenes" --flexsight "$flexsight" --commit "$commit"
step "done: $out/README.md"

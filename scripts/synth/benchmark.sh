#!/usr/bin/env bash
# End-to-end speed of `flexsight synth full` with every output written (rgb, depth,
# masks, COCO, contact sheet), default settings, all cores, at the detector's 300x300
# and at 1280x960; then the per-stage split of one image (Google Benchmark, one thread).
#   scripts/synth/benchmark.sh [COUNT_300 [COUNT_1280]]     (defaults 600 and 60)
# Prints a Markdown table; docs/synth.md quotes it with the machine's CPU.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
flexsight="$root/build/flexsight"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cpu="$(lscpu | sed -n 's/^Model name: *//p' | head -1)"
echo "CPU: $cpu, $(nproc) cores"
echo
echo "| size | images | seconds | images/s | MB written |"
echo "|---|---:|---:|---:|---:|"
for spec in "300x300 ${1:-600}" "1280x960 ${2:-60}"; do
  read -r size count <<<"$spec"
  start=$(date +%s.%N)
  "$flexsight" synth full --count "$count" --size "$size" -o "$work/$size" 2>/dev/null
  end=$(date +%s.%N)
  mb=$(du -sm "$work/$size" | cut -f1)
  awk -v s="$size" -v n="$count" -v a="$start" -v b="$end" -v mb="$mb" \
    'BEGIN { printf "| %s | %d | %.1f | %.1f | %d |\n", s, n, b - a, n / (b - a), mb }'
done
echo
"$root/build/bench/flexsight_bench" --benchmark_filter='BM_Synth_' --benchmark_repetitions=3 \
  --benchmark_report_aggregates_only=true 2>/dev/null | grep -E "median|Benchmark"

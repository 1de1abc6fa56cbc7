#!/usr/bin/env bash
# Builds the Google Benchmark suites and runs both, the OpenCL one (where the build has
# OpenCL) and the reference one, keeping their JSON in docs/benchmark/ and the table
# made from it in docs/benchmark/gbench.md (scripts/stereo/gbench_to_md.py).
#
#   scripts/stereo/run_gbench.sh [extra Google Benchmark flags, e.g. --benchmark_filter=spatial]
#
# Environment: BUILD (build folder, default build/), OUT (default docs/benchmark),
# MIN_TIME (seconds per repetition, default 0.05), REPETITIONS (default 3: the table
# shows medians), FLEXSIGHT_OPENCL_DEVICE (the device, as for the tests). Run it on an
# otherwise idle machine: the reference and PoCL both use every core.
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/../.." && pwd)
BUILD=${BUILD:-$ROOT/build}
OUT=${OUT:-$ROOT/docs/benchmark}
MIN_TIME=${MIN_TIME:-0.05}
REPETITIONS=${REPETITIONS:-3}
JOBS=$(nproc 2>/dev/null || echo 2)

say() { printf '\n== %s\n' "$*"; }

say "building the suites in $BUILD"
nice cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release \
  -DFLEXSIGHT_BUILD_BENCHMARKS=ON >/dev/null
nice cmake --build "$BUILD" -j"$JOBS" --target flexsight_bench
# The OpenCL suite exists only where CMake found an OpenCL SDK.
if nice cmake --build "$BUILD" --target help | grep -q flexsight_bench_opencl; then
  nice cmake --build "$BUILD" -j"$JOBS" --target flexsight_bench_opencl
fi
mkdir -p "$OUT"

# Repetitions are interleaved in random order, so that a burst of other work on the
# machine slows one repetition of several benchmarks (which the median drops) rather
# than every repetition of one.
FLAGS=(--benchmark_out_format=json "--benchmark_repetitions=$REPETITIONS"
       --benchmark_report_aggregates_only=true --benchmark_enable_random_interleaving=true
       "--benchmark_min_time=$MIN_TIME" "$@")

# run_suite NAME EXECUTABLE: prints each benchmark's aggregates as it finishes.
run_suite() {
  local name=$1 executable=$2
  local json="$OUT/gbench-$name.json"
  local count
  count=$("$executable" --benchmark_list_tests "${FLAGS[@]}" | wc -l)
  say "$name suite: $count benchmarks x $REPETITIONS repetitions -> ${json#"$ROOT"/}"
  # Other work on the machine slows the suites down: say how busy it is.
  [[ -r /proc/loadavg ]] && echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
  local start=$SECONDS
  nice "$executable" "--benchmark_out=$json" "${FLAGS[@]}"
  say "$name suite finished in $((SECONDS - start)) s"
}

SUITES_START=$SECONDS
JSONS=()
if [[ -x "$BUILD/bench/flexsight_bench_opencl" ]]; then
  run_suite opencl "$BUILD/bench/flexsight_bench_opencl"
  JSONS+=(--opencl "$OUT/gbench-opencl.json")
else
  say "no OpenCL suite in this build: reference only"
fi
run_suite reference "$BUILD/bench/flexsight_bench"
JSONS+=(--reference "$OUT/gbench-reference.json")
TOTAL=$((SECONDS - SUITES_START))
say "both suites finished in $TOTAL s"

COMMAND="scripts/stereo/run_gbench.sh${*:+ $*} (MIN_TIME=$MIN_TIME REPETITIONS=$REPETITIONS)"
/usr/bin/python3 "$ROOT/scripts/stereo/gbench_to_md.py" "${JSONS[@]}" --command "$COMMAND" \
  --seconds "$TOTAL" >"$OUT/gbench.md"
say "table written to ${OUT#"$ROOT"/}/gbench.md"

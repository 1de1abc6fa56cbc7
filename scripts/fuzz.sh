#!/usr/bin/env bash
# Builds the libFuzzer harnesses of tests/fuzz with clang (ASan + UBSan) in build-fuzz/,
# then runs each on a copy of its seed corpus for SECONDS (default 10), and prints
# harness, inputs run, seconds and findings. docs/reliability.md has the figures.
#
#   scripts/fuzz.sh [SECONDS] [HARNESS...]   e.g. scripts/fuzz.sh 60 pfm coco
#   FUZZ_RUNS=1000000 scripts/fuzz.sh 3600   stop each after a million inputs instead
#
# The committed corpus (tests/fuzz/corpus/<harness>/) is never written: each run works
# on a scratch copy, or, with FUZZ_CORPUS_DIR=DIR, on DIR/<harness>/ (seeded from the
# committed corpus the first time, kept between runs, so a long run can go on where the
# last one stopped). A finding (crash, sanitizer report, leak, time-out over 10 s, more
# than 2 GB) is kept in build-fuzz/findings/<harness>/, its log beside it; re-run one with
# build-fuzz/tests/fuzz/fuzz_<harness> FILE. Exits 1 when there is a finding.
#
# FUZZ_KNOWN_HANGS="harness ...": a time-out in one of these is listed but does not fail
# the run (default: none; the hangs in Assimp and OpenCV's YAML parser are guarded, see
# docs/reliability.md, "Findings"). FUZZ_SKIP="harness ..." leaves harnesses out.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-10}
[ $# -gt 0 ] && shift
runs=${FUZZ_RUNS:--1}
known_hangs=" ${FUZZ_KNOWN_HANGS-} "

scripts/setup.sh --packages-only
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DFLEXSIGHT_FUZZ=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DFLEXSIGHT_BUILD_TESTS=OFF -DFLEXSIGHT_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target flexsight_fuzzers

if [ $# -gt 0 ]; then
  harnesses=("$@")
else
  harnesses=()
  for dir in tests/fuzz/corpus/*/; do
    name=$(basename "$dir")
    [[ " ${FUZZ_SKIP:-} " == *" $name "* ]] || harnesses+=("$name")
  done
fi

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
total_findings=0
rows=()
for name in "${harnesses[@]}"; do
  binary=build-fuzz/tests/fuzz/fuzz_$name
  findings_dir=build-fuzz/findings/$name
  corpus=$scratch/$name
  [ -n "${FUZZ_CORPUS_DIR:-}" ] && corpus=$FUZZ_CORPUS_DIR/$name
  mkdir -p "$findings_dir"
  if [ ! -d "$corpus" ]; then
    mkdir -p "$corpus"
    cp -r "tests/fuzz/corpus/$name/." "$corpus/"
  fi
  log=$findings_dir/last_run.log
  before=$(find "$findings_dir" -type f ! -name '*.log' | wc -l)
  timeouts_before=$(find "$findings_dir" -type f -name 'timeout-*' | wc -l)
  echo "fuzz: $name for ${seconds} s" >&2
  "$binary" "$corpus" -max_total_time="$seconds" -runs="$runs" -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$findings_dir/" >"$log" 2>&1 || true
  executed=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  took=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -1)
  found=$(( $(find "$findings_dir" -type f ! -name '*.log' | wc -l) - before ))
  if [ "$found" -gt 0 ] || ! grep -q '^Done [0-9]* runs' "$log"; then
    [ "$found" -gt 0 ] || found=1  # ended without "Done": a finding even with no artifact
    echo "fuzz: $name: finding, see $log" >&2
    grep -m5 -E 'ERROR|runtime error|terminate|deadly' "$log" >&2 || true
  fi
  timeouts=$(( $(find "$findings_dir" -type f -name 'timeout-*' | wc -l) - timeouts_before ))
  note=""
  if [ "$found" -gt 0 ] && [ "$found" -eq "$timeouts" ] && [[ "$known_hangs" == *" $name "* ]]; then
    note=" (known third-party hang)"
  else
    total_findings=$(( total_findings + found ))
  fi
  rows+=("$(printf '%-20s %12s %8s %9s%s' "$name" "${executed:-?}" "${took:-?}" "$found" "$note")")
done

printf '%-20s %12s %8s %9s\n' harness runs seconds findings
printf '%s\n' "${rows[@]}"
[ "$total_findings" -eq 0 ]

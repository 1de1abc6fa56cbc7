#!/usr/bin/env bash
# Same set-up as scripts/run.sh, then the whole test suite through ctest.
#
# scripts/test.sh --sanitize: the tests of the readers of outside data and of the
# reference stereo path built with GCC's AddressSanitizer and UndefinedBehaviorSanitizer
# (RelWithDebInfo) in build-asan/, any report failing the test that made it.
# docs/reliability.md says what runs there and why.
set -euo pipefail
cd "$(dirname "$0")/.."

if [ "${1:-}" != --sanitize ]; then
  scripts/setup.sh
  ctest --test-dir build --output-on-failure -j"$(nproc)"
  exit 0
fi

scripts/setup.sh --packages-only
start=$(date +%s)
sanitize="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
# Only the tests of the readers of outside data and of the reference (scalar) stereo
# path, in flexsight_sanitize_tests, built with the libraries they need
# (tests/CMakeLists.txt, FLEXSIGHT_SANITIZE_SUBSET; docs/reliability.md says why).
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS="$sanitize" -DCMAKE_EXE_LINKER_FLAGS="$sanitize" \
  -DFLEXSIGHT_BUILD_BENCHMARKS=OFF -DFLEXSIGHT_SANITIZE_SUBSET=ON >/dev/null
cmake --build build-asan -j"$(nproc)" --target flexsight_sanitize_tests
built=$(date +%s)

# Any ASan or UBSan report aborts the process, so it fails its test.
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:strict_string_checks=1:check_initialization_order=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -L '^sanitize$'
echo "sanitize: build $(( built - start )) s, tests $(( $(date +%s) - built )) s"

#!/usr/bin/env bash
# serve's latency benchmark (docs/serve.md, "Benchmark"): `flexsight pick -o` once on a
# bin for the reference answer and time, then `flexsight serve` started on the same
# templates and REQUESTS pick requests from CLIENTS clients (MALFORMED of them malformed)
# through serve_bench.py, which prints the table; SIGTERM at the end, exit code checked.
#
#   scripts/service/bench_serve.sh BIN_DIR TEMPLATES CAD_DIR REQUESTS CLIENTS MALFORMED [KEY=VALUE ...]
#
# KEY=VALUE: pick options of every request (stereo_downscale=4); the CLI gets the same.
set -euo pipefail
[[ $# -ge 6 ]] || { sed -n 2,10p "$0"; exit 1; }
bin=$1 templates=$2 cad=$3 requests=$4 clients=$5 malformed=$6
shift 6
here=$(cd "$(dirname "$0")" && pwd)
flexsight=${FLEXSIGHT:-$here/../../build/flexsight}
work=$(mktemp -d)
trap 'kill "${server:-}" 2>/dev/null || true; rm -rf "$work"' EXIT

cli_options=() bench_options=()
for kv in "$@"; do
  key=${kv%%=*} value=${kv#*=}
  cli_options+=("--${key//_/-}" "$value")
  bench_options+=(--option "$kv")
done
left=$(realpath "$bin/im0.png") right=$(realpath "$bin/im1.png") calib=$(realpath "$bin/calib.txt")

echo "## flexsight pick (the CLI, models loaded by the call)"
/usr/bin/time -f "pick wall %e s" "$flexsight" pick "$left" "$right" --calib "$calib" --templates "$templates" \
  --cad "$cad" --quiet -o "$work/cli.json" "${cli_options[@]}" | sed -n '/| stage/,$p'

"$flexsight" serve --templates "$templates" --cad "$cad" --port 0 --queue 16 --quiet >"$work/serve.out" 2>&1 &
server=$!
for _ in $(seq 600); do grep -q "listening on" "$work/serve.out" && break; sleep 0.5; done
port=$(sed -n 's/.*127\.0\.0\.1:\([0-9]*\).*/\1/p' "$work/serve.out")
[[ -n $port ]] || { cat "$work/serve.out"; exit 1; }
echo; echo "## flexsight serve ($(head -1 "$work/serve.out"))"
python3 "$here/serve_bench.py" --url "http://127.0.0.1:$port" --left "$left" --right "$right" --calib "$calib" \
  --requests "$requests" --clients "$clients" --malformed "$malformed" --expected "$work/cli.json" "${bench_options[@]}"
kill -TERM "$server"
code=0; wait "$server" || code=$?
echo; echo "serve exit code after SIGTERM: $code"
server=

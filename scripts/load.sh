#!/usr/bin/env bash
# Load test of POST /api/analyze with wrk (Debian package `wrk`): a folded square border of
# N = 76 vertices, first the same body again and again (answered from the cache), then a
# fresh body every request (every one analysed). Prints wrk's throughput, latency
# percentiles and error counts.
#
#   scripts/load.sh [DURATION] [CONNECTIONS]      e.g. scripts/load.sh 20s 8
#
# Uses target/release/close (builds it if missing) on a free local port; CLOSE_URL points
# it at a server that already runs instead.
set -euo pipefail
cd "$(dirname "$0")/.."
duration=${1:-15s}
connections=${2:-8}
command -v wrk >/dev/null || { echo "wrk is not installed: apt-get install -y wrk" >&2; exit 1; }

if [[ -z "${CLOSE_URL:-}" ]]; then
  [[ -x target/release/close ]] || cargo build --release
  port=$((20000 + RANDOM % 20000))
  target/release/close serve --addr "127.0.0.1:$port" >/dev/null 2>&1 &
  server=$!
  trap 'kill "$server" 2>/dev/null || true' EXIT
  CLOSE_URL="http://127.0.0.1:$port"
  for _ in $(seq 50); do curl -sf "$CLOSE_URL/healthz" >/dev/null && break; sleep 0.1; done
fi

for mode in cached uncached; do
  echo "== $mode: $duration, $connections connections, 2 threads, N = 76 vertices"
  LOAD_MODE=$mode wrk -t2 -c"$connections" -d"$duration" --latency -s scripts/load.lua "$CLOSE_URL/api/analyze"
  [[ -n "${server:-}" ]] && echo "server RSS: $(ps -o rss= -p "$server") kB"
done

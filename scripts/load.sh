#!/usr/bin/env bash
# Load test with wrk (Debian package `wrk`) of POST /api/analyze, /api/disk and
# /api/interpolate on a folded square of N = 76 vertices (scripts/load.lua): for each route,
# first the same body again and again (answered from the cache where there is one), then a
# new body every request (every one computed). Prints wrk's throughput, latency
# percentiles and error counts, and the server's RSS after each run.
#
#   scripts/load.sh [DURATION] [CONNECTIONS] [ROUTES]   e.g. scripts/load.sh 15s 8 "analyze disk"
#
# Uses target/release/close (builds it if missing) on a free loopback port; CLOSE_URL points
# it at a server that already runs instead.
set -euo pipefail
cd "$(dirname "$0")/.."
duration=${1:-15s}
connections=${2:-8}
routes=${3:-analyze disk interpolate}
command -v wrk >/dev/null || { echo "wrk is not installed: apt-get install -y wrk" >&2; exit 1; }

if [[ -z "${CLOSE_URL:-}" ]]; then
  [[ -x target/release/close ]] || cargo build --release
  port=$((20000 + RANDOM % 20000))
  target/release/close serve --addr "127.0.0.1:$port" >/dev/null 2>&1 &
  server=$!
  trap 'kill "$server" 2>/dev/null || true' EXIT
  CLOSE_URL="http://127.0.0.1:$port"
  for _ in $(seq 50); do curl -sf "$CLOSE_URL/healthz" >/dev/null && break; sleep 0.1; done
  echo "server RSS at start: $(ps -o rss= -p "$server") kB"
fi

for route in $routes; do
  for mode in cached uncached; do
    echo "== /api/$route, $mode: $duration, $connections connections, 2 threads, N = 76 vertices"
    LOAD_ROUTE=$route LOAD_MODE=$mode wrk -t2 -c"$connections" -d"$duration" --latency -s scripts/load.lua "$CLOSE_URL/api/$route"
    [[ -n "${server:-}" ]] && echo "server RSS: $(ps -o rss= -p "$server") kB"
  done
done

#!/usr/bin/env bash
# HTTP load on the active-cluster endpoint with wrk on loopback: starts a server on a copy of
# the sample database, warms the cluster trees, runs wrk per city and prints a table.
#   bench/http_clusters.sh [seconds] [connections]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${TOURMAP_BIN:-$here/build/tourmap}"
seconds="${1:-15}"
connections="${2:-16}"
tmp="$(mktemp -d)"
trap 'kill "$pid" 2>/dev/null || true; rm -rf "$tmp"' EXIT
"$bin" import manifest "$here/scripts/sample-data.json" --data-dir "${TOURMAP_DATA_DIR:-$here/../shared/data}" \
  --db "$tmp/t.db" >/dev/null
"$bin" serve --db "$tmp/t.db" --port 0 --access-log off --rate-limit 0 >"$tmp/out" 2>&1 &
pid=$!
for _ in $(seq 50); do grep -q "listening on" "$tmp/out" && break; sleep 0.1; done
port="$(sed -n 's/.*listening on http:\/\/[^:]*:\([0-9]*\).*/\1/p' "$tmp/out" | head -1)"
echo "| city | POIs | requests/s | p50 | p99 | max | errors |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for city in vienna london berlin; do
  info="$(curl -s "http://127.0.0.1:$port/api/v1/cities/$city")"
  bbox="$(python3 -c 'import json,sys; d=json.loads(sys.argv[1]); print(",".join(str(v) for v in d["poi_bbox"]))' "$info")"
  pois="$(python3 -c 'import json,sys; print(json.loads(sys.argv[1])["counts"]["pois"])' "$info")"
  curl -s "http://127.0.0.1:$port/api/v1/cities/$city/clusters" >/dev/null  # build the tree once
  out="$(CITY="$city" BBOX="$bbox" wrk -t2 -c"$connections" -d"${seconds}s" --latency -s "$here/bench/clusters.lua" "http://127.0.0.1:$port")"
  rps="$(echo "$out" | awk '/Requests\/sec/ {print $2}')"
  p50="$(echo "$out" | awk '$1 == "50%" {print $2}')"
  p99="$(echo "$out" | awk '$1 == "99%" {print $2}')"
  max="$(echo "$out" | awk '/Latency/ && NR < 6 {print $4}')"
  errors="$(echo "$out" | awk '/Non-2xx|Socket errors/ {print}' | tr '\n' ' ')"
  echo "| $city | $pois | $rps | $p50 | $p99 | $max | ${errors:-0} |"
done

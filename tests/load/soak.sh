#!/usr/bin/env bash
# Soak test: the read mix, cluster queries, cached focus deformations (wrk, in parallel) and one
# crowd stream against one server for a long run (5 minutes by default), sampling the server's
# RSS every 10 s. Prints the RSS series and one markdown table (per load: requests/s, p50/p99/max,
# errors), then the verdict: zero errors, and memory bounded (RSS growth from the end of the first
# minute to the end within SOAK_MAX_GROWTH percent, 10 by default). Exits 1 when either fails or
# the server died.
#
#   tests/load/soak.sh [seconds, 300]
#
# Env: TOURMAP_BIN, TOURMAP_DATA_DIR, GZIP=0, DEFORM_ROADS (monaco), CROWD=0 (no crowd stream),
# CROWD_MAX_SUBDIVISION (-1), SOAK_MAX_GROWTH (10). Needs wrk, node 20+, python3, curl.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
load="$here/tests/load"
bin="${TOURMAP_BIN:-$here/build/tourmap}"
data="${TOURMAP_DATA_DIR:-$here/../shared/data}"
seconds="${1:-300}"
max_growth="${SOAK_MAX_GROWTH:-10}"

for tool in wrk node python3 curl; do
  command -v "$tool" >/dev/null || { echo "soak.sh needs $tool" >&2; exit 2; }
done
tmp="$(mktemp -d)"
server_pid=
pids=()
# shellcheck source=tests/load/lib.sh
source "$load/lib.sh"
# shellcheck source=tests/load/warmup.sh
source "$load/warmup.sh"
trap 'for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; tm_stop_server; rm -rf "$tmp"' EXIT
log() { echo "[soak] $*" >&2; }

log "importing the sample data from $data"
"$bin" import manifest "$here/scripts/sample-data.json" --data-dir "$data" --db "$tmp/t.db" >/dev/null
tm_start_server "$tmp/t.db" --data-dir "$data" --rate-limit 0 --max-compute-per-client 0 --crowd-max-subdivision "${CROWD_MAX_SUBDIVISION:--1}"
log "server pid $server_pid on port $port, RSS $(tm_rss)"
tm_warm_up
# shellcheck disable=SC2086  # a list of ids
deform_boxes="$(tm_deform_boxes ${DEFORM_ROADS:-monaco})"
crowd() { node --no-warnings --experimental-websocket "$load/crowd_ws.mjs" --port "$port" "$@"; }
if [[ "${CROWD:-1}" != 0 ]]; then
  log "warm-up: crowd scene office"
  crowd --clients 1 --seconds 1 >/dev/null
fi

url="http://127.0.0.1:$port"
log "soak: $seconds s of read (c=4), clusters (c=4), deform (c=2)$([[ "${CROWD:-1}" != 0 ]] && echo " and one crowd stream")"
wrk -t1 -c4 -d"${seconds}s" -T5s --latency -s "$load/read.lua" "$url" >"$tmp/read.out" 2>&1 &
pids+=($!)
wrk -t1 -c4 -d"${seconds}s" -T5s --latency -s "$load/clusters.lua" "$url" >"$tmp/clusters.out" 2>&1 &
pids+=($!)
ROADS="$deform_boxes" wrk -t1 -c2 -d"${seconds}s" -T5s --latency -s "$load/deform.lua" "$url" >"$tmp/deform.out" 2>&1 &
pids+=($!)
if [[ "${CROWD:-1}" != 0 ]]; then
  crowd --clients 1 --seconds "$seconds" --json >"$tmp/crowd.out" 2>&1 &
  pids+=($!)
fi

# RSS every 10 s while the load runs.
rss_kib() { awk '/^VmRSS:/ {print $2}' "/proc/$server_pid/status" 2>/dev/null || echo 0; }
series=()
start=$(date +%s)
while true; do
  now=$(( $(date +%s) - start ))
  tm_alive || { echo "the server died after $now s; its log:" >&2; tail -20 "$tmp/server.log" >&2; exit 1; }
  series+=("$now $(rss_kib)")
  (( now >= seconds )) && break
  sleep 10
done
for p in "${pids[@]}"; do wait "$p" || true; done
pids=()
tm_alive || { echo "the server died; its log:" >&2; tail -20 "$tmp/server.log" >&2; exit 1; }

echo "RSS (MiB) every 10 s:"
printf '%s\n' "${series[@]}" | awk '{printf "%s s: %.1f\n", $1, $2 / 1024}' | paste -sd ' ' | fold -s -w 100

echo
echo "| load (${seconds} s) | requests/s (or frames/s) | p50 | p99 | max | errors |"
echo "|---|---:|---:|---:|---:|---|"
errors_total=0
for name in read clusters deform; do
  res="$(grep '^RESULT' "$tmp/$name.out" || true)"
  if [[ -z "$res" ]]; then
    echo "| $name | wrk failed | | | | see stderr |"
    cat "$tmp/$name.out" >&2
    errors_total=$((errors_total + 1))
    continue
  fi
  errs=$(( $(tm_field "$res" non2xx) + $(tm_field "$res" connect) + $(tm_field "$res" read) + $(tm_field "$res" write) + $(tm_field "$res" timeout) ))
  errors_total=$((errors_total + errs))
  echo "| $name | $(tm_field "$res" rps) | $(tm_field "$res" p50_ms) ms | $(tm_field "$res" p99_ms) ms | $(tm_field "$res" max_ms) ms | $errs ($(tm_field "$res" statuses)) |"
done
if [[ "${CROWD:-1}" != 0 ]]; then
  line="$(tail -1 "$tmp/crowd.out")"
  if tm_json 'd["fps_total"]' <<<"$line" >/dev/null 2>&1; then
    tm_json '"| crowd stream | %.1f frames/s | %.0f ms | %.0f ms | %.0f ms | %d |" % (d["fps_total"], d["latency_ms"]["p50"], d["latency_ms"]["p99"], d["latency_ms"]["max"], len(d["errors"]))' <<<"$line"
    errors_total=$((errors_total + $(tm_json 'len(d["errors"])' <<<"$line")))
  else
    echo "| crowd stream | failed | | | | see stderr |"
    cat "$tmp/crowd.out" >&2
    errors_total=$((errors_total + 1))
  fi
fi

# Memory: from the first sample at or after 60 s (caches warm) to the last.
verdict="$(printf '%s\n' "${series[@]}" | awk -v max="$max_growth" '
  $1 >= 60 && !base { base = $2; t0 = $1 }
  { last = $2; if ($2 > peak) peak = $2 }
  END {
    if (!base) { base = last; t0 = "end" }
    g = 100 * (last - base) / base
    printf "RSS %.1f MiB at %s s -> %.1f MiB at the end (peak %.1f MiB): %+.1f%% %s\n", base / 1024, t0, last / 1024,
      peak / 1024, g, (g <= max ? "(bounded)" : "(grew more than " max "%)")
    exit g <= max ? 0 : 1
  }')" && bounded=1 || bounded=0
echo
echo "errors: $errors_total"
echo "$verdict"
[[ "$errors_total" == 0 && "$bounded" == 1 ]]

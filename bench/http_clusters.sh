#!/usr/bin/env bash
# HTTP load on the active-cluster endpoint: starts a server (--rate-limit 0, no access log) on a
# copy of the sample database, warms it up like tests/load/run.sh (trees in both spaces), then
# runs wrk with tests/load/clusters.lua (random windows, half geographic, half layout space, m=10)
# with and without `Accept-Encoding: gzip`, and prints one markdown table with throughput and
# latency plus where the CPU went: the server's CPU time and context switches per request (all
# its threads, from /proc) and wrk's CPU, since wrk shares the machine's cores with the server.
#
#   bench/http_clusters.sh [seconds per row, 10] [connections, 16]
#
# Env: TOURMAP_BIN (build/tourmap), TOURMAP_DATA_DIR (../shared/data), WRK_THREADS (1),
# SERVE_ARGS (extra `tourmap serve` options, e.g. "--io-threads 1"), GZIP_MODES ("1 0"),
# WRK_CPUS / SERVER_CPUS (taskset CPU lists to pin wrk or the server, e.g. WRK_CPUS=1),
# ROUNDS (1: rows per mode, interleaved). Needs wrk, python3 and curl.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
load="$here/tests/load"
bin="${TOURMAP_BIN:-$here/build/tourmap}"
data="${TOURMAP_DATA_DIR:-$here/../shared/data}"
seconds="${1:-10}"
connections="${2:-16}"
wrk_threads="${WRK_THREADS:-1}"

for tool in wrk python3 curl; do
  command -v "$tool" >/dev/null || { echo "http_clusters.sh needs $tool" >&2; exit 2; }
done
tmp="$(mktemp -d)"
server_pid=
# shellcheck source=tests/load/lib.sh
source "$load/lib.sh"
# shellcheck source=tests/load/warmup.sh
source "$load/warmup.sh"
trap 'tm_stop_server; rm -rf "$tmp"' EXIT
log() { echo "[clusters] $*" >&2; }

pin() {  # pin CPUS COMMAND...: runs COMMAND under taskset when CPUS is set
  local cpus="$1"
  shift
  if [[ -n "$cpus" ]]; then taskset -c "$cpus" "$@"; else "$@"; fi
}

log "importing the sample data from $data"
"$bin" import manifest "$here/scripts/sample-data.json" --data-dir "$data" --db "$tmp/t.db" >/dev/null
bin_unpinned="$bin"
if [[ -n "${SERVER_CPUS:-}" ]]; then  # tm_start_server runs $bin: pin it through a wrapper
  printf '#!/bin/sh\nexec taskset -c %s %s "$@"\n' "$SERVER_CPUS" "$bin_unpinned" >"$tmp/pinned"
  chmod +x "$tmp/pinned"
  bin="$tmp/pinned"
fi
# shellcheck disable=SC2086  # SERVE_ARGS is a list of options
tm_start_server "$tmp/t.db" --data-dir "$data" --rate-limit 0 --max-compute-per-client 0 ${SERVE_ARGS:-}
log "server pid $server_pid on port $port ($(grep -o '[0-9]* io + [0-9]* read + [0-9]* compute threads' "$tmp/server.log"))"
tm_warm_up

clock_ticks="$(getconf CLK_TCK)"
# CPU time of a process (all threads) in clock ticks, and its context switches (all threads).
cpu_ticks() { awk '{print $14 + $15}' "/proc/$1/stat"; }
ctx_switches() { cat /proc/"$1"/task/*/status | awk '/ctxt_switches/ {n += $2} END {print n}'; }

rows=()
# row GZIP: one wrk run, one table row.
row() {
  local gzip="$1" cpu0 cs0 cpu1 cs1 out res wrk_cpu
  log "clusters, gzip=$gzip: wrk -t$wrk_threads -c$connections -d${seconds}s (load average $(cut -d' ' -f1 /proc/loadavg))"
  cpu0="$(cpu_ticks "$server_pid")"
  cs0="$(ctx_switches "$server_pid")"
  # bash's `times` after wrk: the children's user and system CPU (wrk's, as it is the only child).
  out="$(GZIP="$gzip" pin "${WRK_CPUS:-}" bash -c 'wrk "$@"; times' wrk -t"$wrk_threads" -c"$connections" \
    -d"${seconds}s" -T2s --latency -s "$load/clusters.lua" "http://127.0.0.1:$port" 2>&1)" || true
  cpu1="$(cpu_ticks "$server_pid")"
  cs1="$(ctx_switches "$server_pid")"
  res="$(grep '^RESULT' <<<"$out" || true)"
  if [[ -z "$res" ]]; then
    echo "$out" >&2
    rows+=("| $gzip | wrk failed | | | | | | | | |")
    return
  fi
  wrk_cpu="$(tail -1 <<<"$out" | awk '{ s = 0; for (i = 1; i <= 2; i++) { split($i, p, "m"); sub("s", "", p[2]); s += p[1] * 60 + p[2] } print s }')"
  local n errors
  n="$(tm_field "$res" requests)"
  errors="$(tm_field "$res" non2xx)"
  for k in connect read write timeout; do errors=$((errors + $(tm_field "$res" "$k"))); done
  rows+=("$(awk -v gz="$gzip" -v rps="$(tm_field "$res" rps)" -v p50="$(tm_field "$res" p50_ms)" \
    -v p99="$(tm_field "$res" p99_ms)" -v max="$(tm_field "$res" max_ms)" -v err="$errors" -v n="$n" \
    -v cpu="$((cpu1 - cpu0))" -v hz="$clock_ticks" -v cs="$((cs1 - cs0))" -v wrk="$wrk_cpu" -v s="$seconds" \
    -v load="$(cut -d' ' -f1 /proc/loadavg)" \
    'BEGIN { printf "| %s | %.0f | %.2f ms | %.2f ms | %.2f ms | %d | %.0f %% (%.0f us/req) | %.0f %% (%.0f us/req) | %.2f | %s |",
      gz ? "yes" : "no", rps, p50, p99, max, err, 100 * cpu / hz / s, n ? 1e6 * cpu / hz / n : 0,
      100 * wrk / s, n ? 1e6 * wrk / n : 0, n ? cs / n : 0, load }')")
}

for _ in $(seq "${ROUNDS:-1}"); do
  for gzip in ${GZIP_MODES:-1 0}; do row "$gzip"; done
done
echo "clusters geo+layout, m=10, wrk -t$wrk_threads -c$connections -d${seconds}s${SERVE_ARGS:+, serve $SERVE_ARGS}${WRK_CPUS:+, wrk on CPUs $WRK_CPUS}${SERVER_CPUS:+, server on CPUs $SERVER_CPUS}; $(nproc) cores"
printf '%s\n' "| gzip | requests/s | p50 | p99 | max | errors | server CPU | wrk CPU | server context switches/req | load avg |" \
  "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|" "${rows[@]}"

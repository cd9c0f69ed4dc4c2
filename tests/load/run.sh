#!/usr/bin/env bash
# Load tests: starts `build/tourmap serve` on a free port with a temporary database holding the
# sample data, warms it up (metro layouts, cluster trees, deformation factorization, crowd scene),
# then runs wrk with tests/load/{read,clusters,deform}.lua, the crowd WebSocket client
# tests/load/crowd_ws.mjs, an overload burst on the deform endpoint, and the read mix measured
# while that burst and four MIP layouts run (isolation), and prints one markdown table with
# throughput, latency, errors and the server's RSS (VmRSS) before and after each row.
# Exits non-zero when the server died.
#
#   tests/load/run.sh [seconds per row, 10] [connections, 16]
#
# Env: TOURMAP_BIN (build/tourmap), TOURMAP_DATA_DIR (../shared/data), WRK_THREADS (1: wrk shares
# the cores with the server), GZIP=0 (no Accept-Encoding: gzip), DEFORM_ROADS (monaco),
# CROWD_CLIENTS (6: two over the default stream cap of 4), CROWD_MAX_SUBDIVISION (-1: the scenes'),
# OVERLOAD_CONNECTIONS (512; 256 only fills the default compute queue), OVERLOAD_SECONDS (5),
# RATE_LIMIT (0: the per-client limiter off), MAX_COMPUTE_PER_CLIENT (0: no per-client cap on
# compute requests), ISOLATION_SECONDS (12), SERVE_ARGS (extra `tourmap serve` options),
# ROWS (which rows, default "read clusters deform crowd overload isolation"; e.g. ROWS=clusters
# measures the cluster endpoint alone and skips the deform and crowd warm-ups).
# Needs wrk, node 20+, python3 and curl. Progress goes to stderr, the table to stdout.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
load="$here/tests/load"
bin="${TOURMAP_BIN:-$here/build/tourmap}"
data="${TOURMAP_DATA_DIR:-$here/../shared/data}"
seconds="${1:-10}"
connections="${2:-16}"
wrk_threads="${WRK_THREADS:-1}"
deform_roads="${DEFORM_ROADS:-monaco}"
crowd_clients="${CROWD_CLIENTS:-6}"
overload_connections="${OVERLOAD_CONNECTIONS:-512}"
overload_seconds="${OVERLOAD_SECONDS:-5}"
rows_wanted=" ${ROWS:-read clusters deform crowd overload isolation} "
want() { [[ "$rows_wanted" == *" $1 "* ]]; }

for tool in wrk node python3 curl; do
  command -v "$tool" >/dev/null || { echo "run.sh needs $tool" >&2; exit 2; }
done
tmp="$(mktemp -d)"
server_pid=
# shellcheck source=tests/load/lib.sh
source "$load/lib.sh"
# shellcheck source=tests/load/warmup.sh
source "$load/warmup.sh"
trap 'tm_stop_server; rm -rf "$tmp"' EXIT
log() { echo "[load] $*" >&2; }

log "importing the sample data from $data"
"$bin" import manifest "$here/scripts/sample-data.json" --data-dir "$data" --db "$tmp/t.db" >/dev/null
# All load comes from one address: the per-client rate limiter and the per-client cap on compute
# requests (when the binary has them) are off unless RATE_LIMIT / MAX_COMPUTE_PER_CLIENT say
# otherwise, else every row would measure 429s.
serve_args=(--data-dir "$data" --crowd-max-subdivision "${CROWD_MAX_SUBDIVISION:--1}")
serve_help="$("$bin" serve --help)"
if grep -q -- --rate-limit <<<"$serve_help"; then serve_args+=(--rate-limit "${RATE_LIMIT:-0}"); fi
if grep -q -- --max-compute-per-client <<<"$serve_help"; then
  serve_args+=(--max-compute-per-client "${MAX_COMPUTE_PER_CLIENT:-0}")
fi
# shellcheck disable=SC2086  # SERVE_ARGS is a list of options
tm_start_server "$tmp/t.db" "${serve_args[@]}" ${SERVE_ARGS:-}
url="http://127.0.0.1:$port"
log "server pid $server_pid on port $port, RSS $(tm_rss)"

# --- warm-up: what the rows need computed once, and the boxes the scripts draw windows from ---
tm_warm_up
want deform || want overload || want isolation || deform_roads=
# shellcheck disable=SC2086  # a list of ids
deform_boxes="$(tm_deform_boxes $deform_roads)"
crowd() { node --no-warnings --experimental-websocket "$load/crowd_ws.mjs" --port "$port" "$@"; }
if want crowd; then
  log "warm-up: crowd scene office (the first preparation takes a while on a fresh database)"
  crowd --clients 1 --seconds 1 >/dev/null
fi

# --- rows ---
rows=()
fmt_ms() { awk -v v="$1" 'BEGIN { printf(v < 100 ? "%.2f ms" : "%.0f ms", v) }'; }
print_table() {
  printf '%s\n' "| load | requests/s (or frames/s) | p50 | p99 | max | errors | RSS before | RSS after |" \
    "|---|---:|---:|---:|---:|---|---:|---:|" "${rows[@]}"
}
died() {
  rows+=("| $1 | server died | | | | | $2 | - |")
  print_table
  echo "the server died; its log:" >&2
  tail -20 "$tmp/server.log" >&2
  exit 1
}

# wrk_row LABEL SCRIPT CONNECTIONS SECONDS TIMEOUT KIND [VAR=value...]: one wrk run, one row.
# KIND normal: errors are non-2xx answers and socket errors; overload: 503/429 vs the rest.
wrk_row() {
  local label="$1" script="$2" conns="$3" secs="$4" timeout="$5" kind="$6"
  shift 6
  log "$label: wrk -t$wrk_threads -c$conns -d${secs}s"
  local before out res after
  before="$(tm_rss)"
  out="$(env "$@" wrk -t"$wrk_threads" -c"$conns" -d"${secs}s" -T"$timeout" --latency -s "$load/$script" "$url" 2>&1)" || true
  tm_alive || died "$label" "$before"
  after="$(tm_rss)"
  res="$(grep '^RESULT' <<<"$out" || true)"
  if [[ -z "$res" ]]; then
    echo "$out" >&2
    rows+=("| $label | wrk failed | | | | see stderr | $before | $after |")
    return
  fi
  local non2xx statuses sock
  non2xx="$(tm_field "$res" non2xx)"
  statuses="$(tm_field "$res" statuses)"
  sock="$(for k in connect read write timeout; do v="$(tm_field "$res" $k)"; [[ "$v" == 0 ]] || printf '%s %s, ' "$k" "$v"; done)"
  local errors
  if [[ "$kind" == overload ]]; then
    local n503 n429
    n503="$(tr ',' '\n' <<<"$statuses" | sed -n 's/^503://p')"
    n429="$(tr ',' '\n' <<<"$statuses" | sed -n 's/^429://p')"
    errors="503: ${n503:-0}, 429: ${n429:-0} ($(tm_field "$res" retry_after) with Retry-After), other non-2xx: $((non2xx - ${n503:-0} - ${n429:-0})); timeouts/socket errors: ${sock:-none}"
    errors="${errors%, }"
  elif [[ "$non2xx" == 0 && -z "$sock" ]]; then
    errors=0
  else
    errors="$non2xx non-2xx ($(tr ',' ' ' <<<"$statuses")); socket: ${sock:-none}"
    errors="${errors%, }"
  fi
  local rps
  rps="$(tm_field "$res" rps)"
  if [[ "$kind" == overload ]]; then  # most answers are fast 503s: say how many were served
    rps="$(awk -v n="$(tm_field "$res" requests)" -v bad="$non2xx" -v r="$rps" \
      'BEGIN { printf "%.1f (2xx: %.1f)", r, n ? r * (n - bad) / n : 0 }')"
  fi
  rows+=("| $label | $rps | $(fmt_ms "$(tm_field "$res" p50_ms)") | $(fmt_ms "$(tm_field "$res" p99_ms)") | $(fmt_ms "$(tm_field "$res" max_ms)") | $errors | $before | $after |")
}

if want read; then wrk_row "read mix (c=$connections)" read.lua "$connections" "$seconds" 2s normal; fi
if want clusters; then wrk_row "clusters geo+layout (c=$connections)" clusters.lua "$connections" "$seconds" 2s normal; fi
if want deform; then
  wrk_row "deform focus $deform_roads, cached (c=$connections)" deform.lua "$connections" "$seconds" 2s normal ROADS="$deform_boxes"
fi

# crowd_row: the crowd WebSocket clients, one row.
crowd_row() {
  local label before res after
  label="crowd ws office 640x360 ($crowd_clients clients)"
  log "$label: $seconds s"
  before="$(tm_rss)"
  res="$(crowd --clients "$crowd_clients" --seconds "$seconds" --json || true)"
  tm_alive || died "$label" "$before"
  after="$(tm_rss)"
  if [[ -z "$res" ]]; then
    rows+=("| $label | no frames | | | | see stderr | $before | $after |")
  else
    rows+=("$(tm_json '"| %s | %.1f frames/s total (%s per client) | %.0f ms | %.0f ms | %.0f ms | %d errors, %d refused (1013) | %s | %s |" % (sys.argv[1], d["fps_total"], ", ".join("%.1f" % f for f in d["fps_per_client"]), d["latency_ms"]["p50"], d["latency_ms"]["p99"], d["latency_ms"]["max"], len(d["errors"]), d["refused"], sys.argv[2], sys.argv[3])' <<<"$res" "$label" "$before" "$after")")
    tm_json '"\n".join(d["errors"])' <<<"$res" | sed '/^$/d' >&2
  fi
}
if want crowd; then crowd_row; fi

if want overload; then
  wrk_row "overload: deform (c=$overload_connections, ${overload_seconds} s, timeout 5 s)" deform.lua \
    "$overload_connections" "$overload_seconds" 5s overload ROADS="$deform_boxes"
  sleep 1
  tm_get /healthz >/dev/null || log "after the overload /healthz did not answer 200"
  tm_alive || died "after overload" "$(tm_rss)"
fi

# Isolation (issue 12): the overload burst and four MIP layouts (London, distinct w_r, so none
# is cached) run in the background while the read mix is measured on its own connections. The
# reads run on their own pool and must stay fast whatever the compute pool does.
if want isolation; then
  iso_s="${ISOLATION_SECONDS:-12}"
  log "isolation: overload (c=$overload_connections) + 4 MIP layouts for ${iso_s} s; measuring the read mix"
  env ROADS="$deform_boxes" wrk -t"$wrk_threads" -c"$overload_connections" -d"${iso_s}s" -T5s -s "$load/deform.lua" \
    "$url" >"$tmp/isolation-overload.txt" 2>&1 &
  iso_pids=($!)
  for w_r in 0.12 0.23 0.34 0.45; do
    curl -s -o /dev/null -w "%{http_code} %{time_total}\n" \
      "$url/api/v1/cities/london/layout?solver=mip&time_limit_s=$((iso_s - 2))&w_r=$w_r" >>"$tmp/isolation-mip.txt" &
    iso_pids+=($!)
  done
  sleep 1
  wrk_row "read mix during overload + 4 MIP layouts (c=4)" read.lua 4 "$((iso_s - 3))" 2s normal
  wait "${iso_pids[@]}" || true
  log "isolation: MIP layouts answered (status, seconds): $(tr '\n' ' ' <"$tmp/isolation-mip.txt")"
  tm_alive || died "after isolation" "$(tm_rss)"
fi

print_table

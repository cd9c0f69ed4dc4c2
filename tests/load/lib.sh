# shellcheck shell=bash disable=SC2154  # bin and tmp come from the caller
# Shell helpers for the load tests (sourced by tests/load/run.sh, not run by itself):
# a tourmap server on a free port with a temporary database, its RSS, and JSON field access.
# Needs: $bin (the tourmap binary) and $tmp (a scratch directory the caller removes).

# tm_start_server DB [serve options...]: starts `tourmap serve` on a free port in the background;
# sets server_pid and port. Fails when it does not listen within 10 s.
tm_start_server() {
  local db="$1"
  shift
  "$bin" serve --db "$db" --port 0 --access-log off "$@" >"$tmp/server.log" 2>&1 &
  server_pid=$!
  for _ in $(seq 100); do
    grep -q "listening on" "$tmp/server.log" && break
    kill -0 "$server_pid" 2>/dev/null || break
    sleep 0.1
  done
  port="$(sed -n 's/.*listening on http:\/\/[^:]*:\([0-9]*\).*/\1/p' "$tmp/server.log" | head -1)"
  if [[ -z "$port" ]]; then
    echo "server did not start:" >&2
    cat "$tmp/server.log" >&2
    return 1
  fi
}

# tm_stop_server: SIGTERM (the server drains), then SIGKILL after 5 s.
tm_stop_server() {
  [[ -n "${server_pid:-}" ]] || return 0
  kill "$server_pid" 2>/dev/null || true
  for _ in $(seq 50); do
    kill -0 "$server_pid" 2>/dev/null || break
    sleep 0.1
  done
  kill -9 "$server_pid" 2>/dev/null || true
  wait "$server_pid" 2>/dev/null || true
  server_pid=
}

tm_alive() { [[ -n "${server_pid:-}" ]] && kill -0 "$server_pid" 2>/dev/null; }

# tm_rss: the server's resident set (VmRSS) in MiB, e.g. "41.2 MiB".
tm_rss() {
  awk '/^VmRSS:/ {printf "%.1f MiB", $2 / 1024}' "/proc/$server_pid/status" 2>/dev/null || echo "?"
}

# tm_get PATH: GET http://127.0.0.1:$port PATH, body on stdout; fails on a non-2xx answer.
tm_get() { curl -sf --max-time 600 "http://127.0.0.1:$port$1"; }

# tm_json EXPR [ARG...]: prints the Python expression EXPR with `d` = the JSON document on stdin
# (and the ARGs in sys.argv[1:]).
tm_json() {
  local expr="$1"
  shift
  python3 -c "import json, sys; d = json.load(sys.stdin); print($expr)" "$@"
}

# tm_field LINE KEY: the value of KEY=value in a `RESULT ...` line (see common.lua).
tm_field() { tr ' ' '\n' <<<"$1" | sed -n "s/^$2=//p"; }

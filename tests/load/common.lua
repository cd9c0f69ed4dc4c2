-- Shared by the wrk scripts in tests/load/ (loaded with dofile, not run by itself): counts
-- responses by status in every wrk thread and prints one machine-readable line at the end,
--   RESULT requests=N rps=R p50_ms=.. p99_ms=.. max_ms=.. non2xx=N connect=N read=N write=N timeout=N
--          retry_after=N statuses=200:N,503:N
-- (retry_after: 503/429 answers that carried Retry-After; connect..timeout: wrk's socket errors)
-- which tests/load/run.sh reads (wrk's own summary is printed above it as usual).
-- Env: GZIP=0 drops the `Accept-Encoding: gzip` header the scripts send by default, as browsers do.

local M = {}
local threads = {}

M.headers = {}
if os.getenv("GZIP") ~= "0" then M.headers["Accept-Encoding"] = "gzip" end

-- "a,b,c" -> {a, b, c} (numbers where they are numbers).
function M.split(s)
  local out = {}
  for v in string.gmatch(s or "", "[^,]+") do out[#out + 1] = tonumber(v) or v end
  return out
end

-- "id=x0,y0,x1,y1 id2=..." -> {{id = "id", box = {x0, y0, x1, y1}}, ...}; errors when empty.
function M.boxes(env)
  local out = {}
  for id, box in string.gmatch(os.getenv(env) or "", "([^%s=]+)=([^%s]+)") do
    out[#out + 1] = {id = id, box = M.split(box)}
  end
  if #out == 0 then error(env .. " is not set (id=x0,y0,x1,y1 ...)") end
  return out
end

function M.pick(list)
  return list[math.random(#list)]
end

-- A random window inside box {x0, y0, x1, y1}: width `lo`..`hi` (default 0.02..1) of the box's
-- width, height `aspect` (default 0.6) times the width.
function M.window(b, aspect, lo, hi)
  lo, hi = lo or 0.02, hi or 1
  local w = (b[3] - b[1]) * (lo + (hi - lo) * math.random())
  local h = math.min(b[4] - b[2], w * (aspect or 0.6))
  local x = b[1] + math.random() * math.max(0, b[3] - b[1] - w)
  local y = b[2] + math.random() * math.max(0, b[4] - b[2] - h)
  return string.format("%.6f,%.6f,%.6f,%.6f", x, y, x + w, y + h)
end

function M.get(path)
  return wrk.format("GET", path, M.headers)
end

-- wrk hooks: every script does `setup, init, response, done = M.setup, M.init, M.response, M.done`.
function M.setup(thread)
  thread:set("id", #threads + 1)
  threads[#threads + 1] = thread
end

function M.init(args)
  math.randomseed(7919 * (id or 1))  -- reproducible windows per thread
  statuses, retry_after = {}, 0
end

function M.response(status, headers, body)
  statuses[status] = (statuses[status] or 0) + 1
  if (status == 503 or status == 429) and (headers["Retry-After"] or headers["retry-after"]) then
    retry_after = retry_after + 1
  end
end

function M.done(summary, latency, requests)
  local total, non2xx, retry = {}, 0, 0
  for _, t in ipairs(threads) do
    retry = retry + (t:get("retry_after") or 0)
    for status, n in pairs(t:get("statuses") or {}) do
      total[status] = (total[status] or 0) + n
      if status < 200 or status > 299 then non2xx = non2xx + n end
    end
  end
  local codes = {}
  for status in pairs(total) do codes[#codes + 1] = status end
  table.sort(codes)
  for i, status in ipairs(codes) do codes[i] = status .. ":" .. total[status] end
  local e = summary.errors
  io.write(string.format(
    "RESULT requests=%d rps=%.1f p50_ms=%.2f p99_ms=%.2f max_ms=%.2f non2xx=%d connect=%d read=%d write=%d timeout=%d retry_after=%d statuses=%s\n",
    summary.requests, summary.requests / (summary.duration / 1e6), latency:percentile(50) / 1000,
    latency:percentile(99) / 1000, latency.max / 1000, non2xx, e.connect, e.read, e.write, e.timeout, retry,
    table.concat(codes, ",")))
end

return M

-- wrk script: POST /api/v1/deform/focus on a small road network with one focus circle whose
-- centre moves randomly inside the network's bbox (radius 150..600 m, scale 2..4) and
-- "output":{"roads":"none"}: after the first request every answer re-uses the cached grid and
-- Cholesky factorization (one back-substitution), which is the path measured here.
-- Run (tests/load/run.sh sets the env from /api/v1/roads):
--   ROADS="monaco=7.4043,43.7218,7.4393,43.7520" wrk -t2 -c16 -d10s --latency \
--     -s tests/load/deform.lua http://127.0.0.1:PORT
-- ROADS may list several networks (one is picked per request). Non-2xx answers are counted
-- (RESULT line, see common.lua); the overload row of run.sh reads the 503s from it.
local c = dofile((debug.getinfo(1, "S").source:match("^@(.*/)") or "./") .. "common.lua")
local roads = c.boxes("ROADS")
c.headers["Content-Type"] = "application/json"

request = function()
  local net = c.pick(roads)
  local b = net.box
  local body = string.format(
    '{"roads":"%s","regions":[{"center":[%.6f,%.6f],"radius_m":%.0f,"scale":%.2f}],"output":{"roads":"none"}}',
    net.id, b[1] + math.random() * (b[3] - b[1]), b[2] + math.random() * (b[4] - b[2]),
    150 + 450 * math.random(), 2 + 2 * math.random())
  return wrk.format("POST", "/api/v1/deform/focus", c.headers, body)
end

setup, init, response, done = c.setup, c.init, c.response, c.done

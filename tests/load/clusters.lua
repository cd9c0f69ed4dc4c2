-- wrk script: GET /api/v1/cities/{id}/clusters?bbox=&m=10 with random windows (2..100 % of the
-- extent's width), half in geographic space over the POI extent, half in layout space over the
-- extent of the POIs' warped positions in the city's metro layout (space=layout).
-- Run (tests/load/run.sh sets the env; the layout boxes come from /api/v1/cities/{id}/layout):
--   GEO="london=-0.5,51.3,0.3,51.7 ..." LAYOUT="london=-29000,-30000,37000,21000 ..." \
--     wrk -t2 -c16 -d10s --latency -s tests/load/clusters.lua http://127.0.0.1:PORT
-- LAYOUT may be empty (geo only). Non-2xx answers are counted (RESULT line, see common.lua).
local c = dofile((debug.getinfo(1, "S").source:match("^@(.*/)") or "./") .. "common.lua")
local geo = c.boxes("GEO")
local layout = (os.getenv("LAYOUT") or "") ~= "" and c.boxes("LAYOUT") or {}

request = function()
  if #layout > 0 and math.random() < 0.5 then
    local city = c.pick(layout)
    return c.get("/api/v1/cities/" .. city.id .. "/clusters?space=layout&m=10&bbox=" .. c.window(city.box))
  end
  local city = c.pick(geo)
  return c.get("/api/v1/cities/" .. city.id .. "/clusters?m=10&bbox=" .. c.window(city.box))
end

setup, init, response, done = c.setup, c.init, c.response, c.done

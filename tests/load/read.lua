-- wrk script: a mix of map reads over the imported cities and road networks, with random windows.
--   10 % GET /api/v1/cities          15 % GET /api/v1/cities/{id}
--   25 % GET /api/v1/cities/{id}/metro   25 % GET /api/v1/cities/{id}/pois?bbox=
--   25 % GET /api/v1/roads/{id}?bbox=   (windows 2..30 % of the network's width: zoomed-in views)
-- Run (tests/load/run.sh sets the env from /api/v1/cities and /api/v1/roads):
--   CITIES="vienna=16.2,48.1,16.5,48.3 ..." ROADS="monaco=7.40,43.72,7.44,43.75 ..." \
--     wrk -t2 -c16 -d10s --latency -s tests/load/read.lua http://127.0.0.1:PORT
-- Non-2xx answers are counted (RESULT line, see common.lua).
local c = dofile((debug.getinfo(1, "S").source:match("^@(.*/)") or "./") .. "common.lua")
local cities, roads = c.boxes("CITIES"), c.boxes("ROADS")

request = function()
  local r = math.random()
  if r < 0.10 then return c.get("/api/v1/cities") end
  if r < 0.75 then
    local city = c.pick(cities)
    if r < 0.25 then return c.get("/api/v1/cities/" .. city.id) end
    if r < 0.50 then return c.get("/api/v1/cities/" .. city.id .. "/metro") end
    return c.get("/api/v1/cities/" .. city.id .. "/pois?bbox=" .. c.window(city.box))
  end
  local net = c.pick(roads)
  return c.get("/api/v1/roads/" .. net.id .. "?bbox=" .. c.window(net.box, 0.6, 0.02, 0.3))
end

setup, init, response, done = c.setup, c.init, c.response, c.done

-- wrk script: GET /api/v1/cities/<city>/clusters with random windows inside the city's POI extent.
-- wrk -t2 -c16 -d20s -s bench/clusters.lua http://127.0.0.1:PORT  (env CITY, BBOX="minlon,minlat,maxlon,maxlat")
local city = os.getenv("CITY") or "london"
local b = {}
for v in string.gmatch(os.getenv("BBOX") or "-0.5,51.3,0.3,51.7", "[^,]+") do b[#b + 1] = tonumber(v) end
math.randomseed(7)
request = function()
  local w = (b[3] - b[1]) * (0.02 + 0.98 * math.random())
  local h = w * 0.6
  local x = b[1] + math.random() * math.max(0, b[3] - b[1] - w)
  local y = b[2] + math.random() * math.max(0, b[4] - b[2] - h)
  local path = string.format("/api/v1/cities/%s/clusters?bbox=%.5f,%.5f,%.5f,%.5f&m=10", city, x, y, x + w, y + h)
  return wrk.format("GET", path)
end

-- wrk script for scripts/load.sh: a folded square of 76 vertices, posted to
--   LOAD_ROUTE=analyze      POST /api/analyze      the Sample JSON (start and folded frames)
--   LOAD_ROUTE=disk         POST /api/disk         the folded border against the flat one, 480 px
--   LOAD_ROUTE=interpolate  POST /api/interpolate  the flat border, 41 steps (as the web app)
-- LOAD_MODE=cached sends one body again and again (the server answers from its cache where
-- it has one); LOAD_MODE=uncached makes every body new (a new name, or coordinates and
-- angles moved by a few 1e-9), so every request is computed afresh.

local per_side = 19 -- 4 × 19 = 76 vertices

local function square(offset)
  local flat, folded = {}, {}
  local corners = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } }
  for c = 1, 4 do
    local a, b = corners[c], corners[c % 4 + 1]
    for k = 0, per_side - 1 do
      local t = k / per_side
      local x, y = a[1] + t * (b[1] - a[1]) + offset, a[2] + t * (b[2] - a[2])
      flat[#flat + 1] = string.format("[%.10f,%.10f,0]", x, y)
      -- Fold in half along x = 0.4: the right part lands on the left, one layer up.
      if x > 0.4 then
        folded[#folded + 1] = string.format("[%.10f,%.10f,0.01]", 0.8 - x, y)
      else
        folded[#folded + 1] = string.format("[%.10f,%.10f,0]", x, y)
      end
    end
  end
  return "[" .. table.concat(flat, ",") .. "]", "[" .. table.concat(folded, ",") .. "]"
end

local route = os.getenv("LOAD_ROUTE") or "analyze"

local function body(name, k)
  local flat, folded = square(k * 1e-9)
  if route == "disk" then
    return string.format('{"border":%s,"reference":%s,"size":480}', folded, flat)
  elseif route == "interpolate" then
    return string.format('{"border":%s,"from":[%.9f,3.6],"to":[1.0,4.0],"steps":41}', flat, 0.5 + k * 1e-9)
  end
  return string.format('{"name":"%s","category":"napkin","frames":[%s,%s]}', name, flat, folded)
end

local threads = {}
function setup(thread)
  thread:set("id", #threads + 1)
  threads[#threads + 1] = thread
end

local uncached = os.getenv("LOAD_MODE") == "uncached"
local same = body("load test", 0)
local counter = 0

function init(args)
  wrk.method = "POST"
  wrk.headers["Content-Type"] = "application/json"
end

function request()
  if uncached then
    counter = counter + 1
    return wrk.format(nil, nil, nil, body(string.format("load %d-%d", id, counter), id * 1000000 + counter))
  end
  return wrk.format(nil, nil, nil, same)
end

-- wrk script for scripts/load.sh: POST /api/analyze with a folded square of 76 vertices.
-- LOAD_MODE=cached sends one body again and again (the server answers from its cache);
-- LOAD_MODE=uncached gives every request its own name, so every body hashes differently
-- and is analysed afresh.

local per_side = 19 -- 4 × 19 = 76 vertices

local function square_sample(name)
  local flat, folded = {}, {}
  local corners = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } }
  for c = 1, 4 do
    local a, b = corners[c], corners[c % 4 + 1]
    for k = 0, per_side - 1 do
      local t = k / per_side
      local x, y = a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])
      flat[#flat + 1] = string.format("[%.6f,%.6f,0]", x, y)
      -- Fold in half along x = 0.4: the right part lands on the left, one layer up.
      if x > 0.4 then
        folded[#folded + 1] = string.format("[%.6f,%.6f,0.01]", 0.8 - x, y)
      else
        folded[#folded + 1] = string.format("[%.6f,%.6f,0]", x, y)
      end
    end
  end
  return string.format('{"name":"%s","category":"napkin","frames":[[%s],[%s]]}', name, table.concat(flat, ","), table.concat(folded, ","))
end

local threads = {}
function setup(thread)
  thread:set("id", #threads + 1)
  threads[#threads + 1] = thread
end

local uncached = os.getenv("LOAD_MODE") == "uncached"
local body = square_sample("load test")
local counter = 0

function init(args)
  wrk.method = "POST"
  wrk.headers["Content-Type"] = "application/json"
end

function request()
  if uncached then
    counter = counter + 1
    return wrk.format(nil, nil, nil, square_sample(string.format("load %d-%d", id, counter)))
  end
  return wrk.format(nil, nil, nil, body)
end

-- Every setter of a simulation refuses what its constructor key refuses.
-- The setters are found in the simulation's method table (every name
-- starting with set_, plus the other methods that change numbers listed in
-- `mutators`): a setter without a case here fails the deck. Each case is
-- called with NaN, inf, -inf and, where the key has a bound, a value beyond
-- it; each call must be refused with
--   setters.lua:LINE: WHERE: KEY = VALUE is out of range (expected RANGE)
-- naming the line of the call, the key and the expected range. Where the key
-- exists in simulation{} too, the constructor refuses the same value with
-- the same words after its own WHERE (one shared check per key). A refused
-- call changes nothing.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local grid = { size = { 1, 1 }, cell = 0.1 }
local function new_sim(extra)
  local t = { dim = 2, grid = grid, thermo = 0, diagnostics = false, series = false }
  for k, v in pairs(extra or {}) do t[k] = v end
  return mpm.simulation(t)
end
local sim = new_sim()
sim:add_particles(mpm.box{ min = { 0.2, 0.2 }, max = { 0.6, 0.6 } }, { material = mat })
sim:particle_field{ name = "damage" }
sim:constrain{ region = mpm.box{ min = { 0, 0 }, max = { 1, 0.1 } }, vx = 0 }
sim:add_wall{ name = "plate", shape = "plane", point = { 0, 0.05 }, normal = { 0, 1 } }

-- finite: the range named for NaN and the infinities; bad, range: a finite
-- value beyond the bound and the range named for it (nil: only finiteness)
local cases = {
  set_gravity = {
    { where = "set_gravity()", key = "gravity[1]", finite = "a finite value, in m/s^2",
      call = function(s, v) s:set_gravity{ v, 0 } end,
      ctor = function(v) new_sim{ gravity = { v, 0 } } end, ctor_where = "simulation{}" },
  },
  set_boundary = {
    { where = "set_boundary() boundary", key = "mu", finite = "a finite value >= 0", bad = -0.5, range = "a value >= 0",
      call = function(s, v) s:set_boundary{ left = { "friction", mu = v } } end,
      ctor = function(v) new_sim{ boundary = { left = { "friction", mu = v } } } end,
      ctor_where = "simulation{} boundary" },
    { where = "set_boundary() boundary left", key = "v[2]", finite = "a finite value, in m/s",
      call = function(s, v) s:set_boundary{ left = { "velocity", v = { 0, v } } } end,
      ctor = function(v) new_sim{ boundary = { left = { "velocity", v = { 0, v } } } } end,
      ctor_where = "simulation{} boundary left" },
  },
  set_scheme = {
    { where = "set_scheme()", key = "flip_fraction", finite = "a value in [0, 1]", bad = 1.5, range = "a value in [0, 1]",
      call = function(s, v) s:set_scheme{ flip_fraction = v } end,
      ctor = function(v) new_sim{ scheme = { flip_fraction = v } } end, ctor_where = "simulation{} scheme" },
  },
  set_dt = {
    { where = "set_dt()", key = "dt", finite = "a finite value > 0, in s", bad = -1, range = "a value > 0, in s",
      call = function(s, v) s:set_dt(v) end,
      ctor = function(v) new_sim{ dt = v } end, ctor_where = "simulation{}" },
    { where = "set_dt() dt", key = "fixed", finite = "a finite value > 0, in s", bad = 0, range = "a value > 0, in s",
      call = function(s, v) s:set_dt{ fixed = v } end,
      ctor = function(v) new_sim{ dt = { fixed = v } } end, ctor_where = "simulation{} dt" },
    { where = "set_dt() dt", key = "max", finite = "a finite value >= 0, in s", bad = -1, range = "a value >= 0, in s",
      call = function(s, v) s:set_dt{ cfl = 0.5, max = v } end,
      ctor = function(v) new_sim{ dt = { cfl = 0.5, max = v } } end, ctor_where = "simulation{} dt" },
  },
  set_damping = {
    { where = "set_damping() damping", key = "cundall", finite = "a finite value >= 0", bad = -0.1, range = "a value >= 0",
      call = function(s, v) s:set_damping{ cundall = v } end,
      ctor = function(v) new_sim{ damping = { cundall = v } } end, ctor_where = "simulation{} damping" },
    { where = "set_damping() damping", key = "viscous", finite = "a finite value >= 0, in 1/s", bad = -2,
      range = "a value >= 0, in 1/s",
      call = function(s, v) s:set_damping{ viscous = v } end,
      ctor = function(v) new_sim{ damping = { viscous = v } } end, ctor_where = "simulation{} damping" },
  },
  set_split = {
    { where = "set_split() split", key = "stretch", finite = "a finite value > 1", bad = 0.5, range = "a value > 1",
      call = function(s, v) s:set_split{ stretch = v } end,
      ctor = function(v) new_sim{ split = { stretch = v } } end, ctor_where = "simulation{} split" },
  },
  set_parallel = {
    { where = "set_parallel()", key = "imbalance", finite = "a finite value >= 1", bad = 0.5, range = "a value >= 1",
      call = function(s, v) s:set_parallel{ imbalance = v } end },
  },
  set_watchdog = {
    { where = "set_watchdog() watchdog", key = "energy", finite = "a finite value >= 0", bad = -1, range = "a value >= 0",
      call = function(s, v) s:set_watchdog{ energy = v } end,
      ctor = function(v) new_sim{ watchdog = { energy = v } } end, ctor_where = "simulation{} watchdog" },
    { where = "set_watchdog() watchdog", key = "speed", finite = "a finite value >= 0, in cells", bad = -1,
      range = "a value >= 0, in cells",
      call = function(s, v) s:set_watchdog{ speed = v } end,
      ctor = function(v) new_sim{ watchdog = { speed = v } } end, ctor_where = "simulation{} watchdog" },
  },
  set_constraint = {
    { where = "set_constraint()", key = "vx", finite = "a finite value, in m/s",
      call = function(s, v) s:set_constraint(1, { vx = v }) end },
  },
  set_wall = {
    { where = "set_wall()", key = "velocity[1]", finite = "a finite value, in m/s",
      call = function(s, v) s:set_wall("plate", { velocity = { v, 0 } }) end },
    { where = "set_wall()", key = "omega", finite = "a finite value, in rad/s",
      call = function(s, v) s:set_wall("plate", { omega = v }) end },
  },
  set_value = {
    { where = "set_value()", key = "damage", finite = "a finite value",
      call = function(s, v) s:set_value("damage", 1, v) end },
  },
  set_field = {
    { where = "set_field()", key = "damage", finite = "a finite value",
      call = function(s, v) s:set_field("damage", v) end },
    { where = "set_field()", key = "damage", finite = "a finite value",
      call = function(s, v) s:set_field("damage", function() return v end) end },
  },
  -- the methods not named set_ that change numbers of the simulation
  load_factor = {
    { where = "load_factor()", key = "factor", finite = "a finite value",
      call = function(s, v) s:load_factor(v) end },
  },
  output = {
    { where = "output() output", key = "every", finite = "a finite value > 0, in s", bad = -1, range = "a value > 0, in s",
      call = function(s, v) s:output{ every = v } end,
      ctor = function(v) new_sim{ output = { every = v } } end, ctor_where = "simulation{} output" },
  },
  point_force = {
    { where = "point_force{}", key = "force[1]", finite = "a finite value, in N",
      call = function(s, v) s:point_force{ region = mpm.box{ min = { 0.2, 0.2 }, max = { 0.3, 0.3 } }, force = { v, 0 } } end },
  },
  constrain = {
    { where = "constrain{}", key = "vy", finite = "a finite value, in m/s",
      call = function(s, v) s:constrain{ region = mpm.box{ min = { 0, 0.9 }, max = { 1, 1 } }, vy = v } end },
  },
}
local mutators = { "load_factor", "output", "point_force", "constrain" }

-- every setter of the method table has a case, and every case a method
local methods = getmetatable(sim).__index
local setters = {}
for name in pairs(methods) do
  if name:match("^set_") then setters[#setters + 1] = name end
end
table.sort(setters)
T.check(#setters >= 8, "only %d set_ methods found in the method table", #setters)
for _, name in ipairs(mutators) do setters[#setters + 1] = name end
for name in pairs(cases) do
  T.check(rawget(methods, name) ~= nil, "a case for '%s', which is not a method of the simulation", name)
end

local function spelt(v)
  if v ~= v then return "NaN" end
  if v == math.huge then return "inf" end
  if v == -math.huge then return "-inf" end
  return string.format("%g", v)
end

-- the message of fn(v), which must fail
local function refusal(fn, v)
  local ok, msg = pcall(fn, v)
  T.check(not ok, "the value %s was accepted", spelt(v))
  return msg
end

local deck = debug.getinfo(1, "S").short_src -- the deck path as moraine was given it
local walked = 0
for _, name in ipairs(setters) do
  T.check(cases[name] ~= nil, "setter sim:%s has no case in setters.lua (add one with its constructor key)", name)
  for _, c in ipairs(cases[name]) do
    local line = debug.getinfo(c.call, "S").linedefined
    local values = { { 0 / 0, c.finite }, { math.huge, c.finite }, { -math.huge, c.finite } }
    if c.bad then values[#values + 1] = { c.bad, c.range } end
    for _, pair in ipairs(values) do
      local v, range = pair[1], pair[2]
      local detail = string.format("%s = %s is out of range (expected %s)", c.key, spelt(v), range)
      local msg = refusal(function(x) c.call(sim, x) end, v)
      local expected = string.format("%s:%d: %s: %s", deck, line, c.where, detail)
      T.check(msg == expected, "sim:%s(%s):\n  got      %s\n  expected %s", name, spelt(v), msg, expected)
      if c.ctor then
        local ctor_msg = refusal(c.ctor, v)
        local tail = string.format("%s: %s", c.ctor_where, detail)
        T.check(ctor_msg:sub(-#tail) == tail, "the constructor key of sim:%s(%s):\n  got      %s\n  expected ...%s",
                name, spelt(v), ctor_msg, tail)
      end
      walked = walked + 1
    end
  end
end

-- a refused setter leaves the value it would have changed
local g = sim:info().gravity
T.check(g[1] == 0 and g[2] == 0, "set_gravity changed the gravity to {%s, %s} while refusing", g[1], g[2])
T.check(sim:value("damage", 1) == 0, "set_value changed the field while refusing")
-- set_field reads and checks every value before it stores one
local values = {}
for i = 1, sim:particle_count() do values[i] = 7 end
values[#values] = 0 / 0
T.check(not pcall(sim.set_field, sim, "damage", values), "set_field accepted a NaN among its values")
T.check(sim:value("damage", 1) == 0, "a refused set_field stored the values before the NaN")
T.check(not pcall(sim.set_field, sim, "damage", function(x, y, z, i) return i == 5 and 1 / 0 or 7 end),
        "set_field accepted an inf from its function")
T.check(sim:value("damage", 1) == 0, "a refused set_field stored the function's values before the inf")
print(string.format("setters: %d setters, %d refusals", #setters, walked))
T.done("setters")

-- A material written in Lua (mpm.material.lua{}) against the C model it
-- copies: a Hooke's law in Lua gives the particle stresses of
-- linear_elastic to round-off, on a deck (an elastic block thrown spinning
-- onto a floor, 2D and 3D) and at the single-point driver (a path with
-- rotation). Its history variables are kept per particle and survive a
-- checkpoint bit for bit; an error in its function stops the run with the
-- deck line.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local rho, E, nu = 1000, 1e6, 0.3
local lambda, G = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))

-- Hooke's law as linear_elastic writes it, plus a history variable: the
-- accumulated volumetric strain
local function hooke(b)
  for i = 1, b.n do
    local s, d = b.stress[i], b.dstrain[i]
    local tr = d[1] + d[2] + d[3]
    for k = 1, 3 do s[k] = s[k] + (lambda * tr + 2.0 * G * d[k]) end
    for k = 4, 6 do s[k] = s[k] + 2.0 * G * d[k] end
    b.state[i].eps_v = b.state[i].eps_v + tr
  end
end
local c_p = math.sqrt((lambda + 2 * G) / rho)
local lua_mat = mpm.material.lua{ name = "hooke", density = rho, wave_speed = c_p, state = { "eps_v" },
                                  update = hooke }
local c_mat = mpm.material.linear_elastic{ density = rho, E = E, nu = nu }
T.check(lua_mat.model == "lua" and lua_mat.name == "hooke", "material fields: %s", tostring(lua_mat))

local function block(dim, mat, name)
  local size = dim == 2 and { 1, 1 } or { 1, 1, 1 }
  local sim = mpm.simulation{ dim = dim, grid = { size = size, cell = 0.1 }, gravity = dim == 2 and { 0, -9.81 } or { 0, -9.81, 0 },
    scheme = { transfer = "FLIP", stress_update = "USL" }, dt = { fixed = 2e-4 }, boundary = { all = "fixed" }, thermo = 0, diagnostics = false,
    series = false, name = name }
  local lo, hi = dim == 2 and { 0.3, 0.2 } or { 0.3, 0.2, 0.3 }, dim == 2 and { 0.7, 0.6 } or { 0.7, 0.6, 0.7 }
  sim:add_particles(mpm.box{ min = lo, max = hi }, { material = mat, per_axis = 2,
    velocity = function(x, y, z) return -3 * (y - 0.4), 3 * (x - 0.5) - 1, 0 end })
  return sim
end

local function worst_difference(a, b, field)
  local x, y = a:field(field), b:field(field)
  T.check(#x == #y and #x > 0, "%s: sizes %d, %d", field, #x, #y)
  local scale, worst = 0, 0
  for i = 1, #x do scale = math.max(scale, math.abs(x[i])) end
  for i = 1, #x do worst = math.max(worst, math.abs(x[i] - y[i])) end
  return worst / scale, scale
end

for _, dim in ipairs{ 2, 3 } do
  local a, b = block(dim, c_mat, "c" .. dim), block(dim, lua_mat, "lua" .. dim)
  a:run{ steps = 400 }
  b:run{ steps = 400 }
  for _, f in ipairs{ "stress", "velocity", "displacement" } do
    local rel, scale = worst_difference(a, b, f)
    T.expect{ id = "lua_material.deck" .. dim .. "." .. f, what = dim .. "D " .. f .. " (Lua vs C, max |diff| / max |value|)",
              value = rel, max = 1e-12 }
    print(string.format("lua material %dD: %s differs by %.3g relative (scale %.3g)", dim, f, rel, scale))
  end
end

-- the driver: a path with spin and stretch, Lua against C, and the history
-- variable equal to the trace of the accumulated strain
local da, db = mpm.driver{ material = c_mat }, mpm.driver{ material = lua_mat }
local worst = 0
for step = 1, 200 do
  local t = step * 1e-3
  local L = { 0.3 * math.sin(t), 2.0, 0.1, -1.5, -0.2 * math.cos(3 * t), 0.4, 0.05, -0.3, 0.1 }
  da:step(L, 1e-3)
  db:step(L, 1e-3)
end
local sa, sb, scale = da.stress, db.stress, 0
for k = 1, 6 do scale = math.max(scale, math.abs(sa[k])) end
for k = 1, 6 do worst = math.max(worst, math.abs(sa[k] - sb[k]) / scale) end
T.expect{ id = "lua_material.driver", what = "driver stress (Lua vs C, max |diff| / max |stress|)", value = worst,
          max = 1e-12 }
local e = db.strain
T.close(db.state.eps_v, e[1] + e[2] + e[3], 1e-12, "driver history variable eps_v")
T.close(db.e_elastic, da.e_elastic, 1e-10, "driver elastic energy")
print(string.format("lua material driver: stress differs by %.3g relative; eps_v %.6g", worst, db.state.eps_v))

-- a history variable that the stress depends on (a stiffness that grows
-- with the accumulated |volumetric strain|) survives a checkpoint: N steps,
-- save, load, N more give the particles of 2N steps bit for bit
local function hardening(b)
  for i = 1, b.n do
    local s, d, st = b.stress[i], b.dstrain[i], b.state[i]
    local tr = d[1] + d[2] + d[3]
    local f = 1 + 100 * st.k
    for k = 1, 3 do s[k] = s[k] + f * (lambda * tr + 2.0 * G * d[k]) end
    for k = 4, 6 do s[k] = s[k] + f * 2.0 * G * d[k] end
    st.k = st.k + math.abs(tr)
  end
end
local hard = mpm.material.lua{ name = "hardening", density = rho, wave_speed = 2 * c_p, state = { "k" },
                               update = hardening }
local straight = block(2, hard, "straight")
straight:run{ steps = 100 }
local path = straight:save("lua_material_100.h5")
straight:run{ steps = 100 }
local resumed = mpm.load(path, { diagnostics = false, thermo = 0 })
resumed:run{ steps = 100 }
for _, f in ipairs{ "stress", "velocity", "displacement", "deformation_gradient" } do
  local x, y = straight:field(f), resumed:field(f)
  for i = 1, #x do T.check(x[i] == y[i], "restart: %s[%d] differs: %.17g vs %.17g", f, i, x[i], y[i]) end
end
local moved = straight:field("stress")
local differs = false
local plain = block(2, lua_mat, "plain")
plain:run{ steps = 200 }
local p = plain:field("stress")
for i = 1, #p do differs = differs or p[i] ~= moved[i] end
T.check(differs, "the history variable changes nothing: the restart test would not see it lost")

T.done("lua_material")

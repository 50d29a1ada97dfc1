-- Walls, rigid bodies and contact between bodies on 1, 2 and 3 processes
-- (tests/parallel/equivalence.py runs it under mpirun and compares). The
-- slabs are cut along y, so each case puts its contact across the cuts:
--   case=incline  an elastic block sliding down (from 1 m/s) a 30 degree
--                 plane wall with friction (mu = 0.3, gap_check) that moves
--                 along itself, FLIP/USF:
--                 the plane's contact columns lie across the rows the cuts
--                 fall in;
--   case=push     a box rigid body (free in x and rz) pushed by a constant
--                 external force against the side of an elastic column
--                 standing on a friction floor, APIC/USL: the contact is a
--                 vertical face over the column's height;
--   case=blocks   two elastic blocks colliding sideways with friction
--                 (mu = 0.2) while sliding past each other vertically,
--                 FLIP/MUSL: the interface is vertical over their height.
-- Writes the diagnostics (with the walls' columns) every step (NAME.csv)
-- and the final state (NAME.h5, sim:save: the particles and the walls);
-- --set load=FILE continues from a checkpoint of the incline or the push
-- instead (tests/parallel/restart.py; a simulation read with mpm.load has
-- no contact pairs, doc/lua-api.md).
local case = mpm.param("case", "incline")
local steps = mpm.param("steps", 300)
local name = mpm.param("name", case)
local rebalance = mpm.param("rebalance", 0)
local load = mpm.param("load", "")
local elastic = mpm.material.linear_elastic{ density = 1000, E = 2e5, nu = 0.3 }
local sim
if load ~= "" then
  sim = mpm.load(load, { thermo = 0, diagnostics = name .. ".csv" })
elseif case == "incline" then
  local th = math.rad(30)
  local t, n = { math.cos(th), math.sin(th) }, { -math.sin(th), math.cos(th) }
  -- the plane through (0, 0.1), rising to the right; the block on it, 0.3 m along it, 0.12 m thick
  local function at(s, h) return { s * t[1] + h * n[1], 0.1 + s * t[2] + h * n[2] } end
  sim = mpm.simulation{ dim = 2, grid = { size = { 1.2, 0.8 }, cell = 0.02 }, shape = "quadratic_bspline",
    scheme = { transfer = "FLIP", stress_update = "USF" }, gravity = { 0, -9.81 },
    boundary = { all = "slip", top = "free" }, dt = { cfl = 0.4 }, thermo = 0, diagnostics = name .. ".csv",
    diagnostics_every = 1 }
  sim:add_wall{ name = "slope", shape = "plane", point = { 0, 0.1 }, normal = n, kind = "friction", mu = 0.3,
                gap_check = true, velocity = { 0.2 * t[1], 0.2 * t[2] } }
  sim:add_particles(mpm.polygon{ vertices = { at(0.6, 0), at(0.9, 0), at(0.9, 0.12), at(0.6, 0.12) } },
                    { material = elastic, per_axis = 2, velocity = { -t[1], -t[2] } })
elseif case == "push" then
  sim = mpm.simulation{ dim = 2, grid = { size = { 1.0, 0.8 }, cell = 0.02 }, shape = "quadratic_bspline",
    scheme = { transfer = "APIC", stress_update = "USL" }, gravity = { 0, -9.81 },
    boundary = { all = "slip", bottom = { "friction", mu = 0.5 }, top = "free" }, dt = { cfl = 0.4 },
    thermo = 0, diagnostics = name .. ".csv", diagnostics_every = 1 }
  sim:add_particles(mpm.box{ min = { 0.3, 0 }, max = { 0.5, 0.6 } }, { material = elastic, per_axis = 2 })
  -- its weight carried by the fixing in y; free to turn as the column pushes back unevenly
  sim:add_wall{ name = "pusher", shape = "box", min = { 0.51, 0.1 }, max = { 0.61, 0.55 }, density = 500,
                fix = { "y" }, velocity = { -0.1, 0 }, external_force = { -300, 0 } }
elseif case == "blocks" then
  sim = mpm.simulation{ dim = 2, grid = { size = { 1.0, 0.8 }, cell = 0.02 }, shape = "quadratic_bspline",
    scheme = { transfer = "FLIP", stress_update = "MUSL" }, gravity = { 0, 0 },
    boundary = { all = "slip" }, dt = { cfl = 0.4 }, thermo = 0, diagnostics = name .. ".csv",
    diagnostics_every = 1 }
  sim:add_particles(mpm.box{ min = { 0.2, 0.1 }, max = { 0.45, 0.6 } },
                    { material = elastic, per_axis = 2, body = "left", velocity = { 0.5, 0.3 } })
  sim:add_particles(mpm.box{ min = { 0.47, 0.2 }, max = { 0.67, 0.7 } },
                    { material = elastic, per_axis = 2, body = "right", velocity = { -0.4, -0.2 } })
  sim:add_contact{ bodies = { "left", "right" }, mu = 0.2 }
else
  error("case must be incline, push or blocks, got " .. tostring(case))
end
if rebalance > 0 then sim:set_parallel{ rebalance_every = rebalance, imbalance = 1.0 } end
sim:run{ steps = steps }
local par = dofile(mpm.deck_dir .. "/finish.lua")(sim, name)

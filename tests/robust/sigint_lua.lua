-- Lua code that never returns to the engine, for tests/robust/sigint_lua.sh,
-- which sends one SIGINT once the file "started" exists. --set mode=
--   loop    an endless Lua loop after a run of 3 steps (the state to keep)
--   hook    a hook that loops for ever from step 10 of a run
--   c_hook  a hook that spends about a second inside one C function from
--           step 10: the signal waits for it, then stops the run
--   seed    a seeding of 6.4e7 points (a thin ring in a wide box, counted
--           before it is seeded): the signal stops it between rows of cells
local mode = mpm.param("mode", "loop")
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, thermo = 0, name = mode,
  diagnostics = false }
sim:add_particles(mpm.box{ min = { 0.2, 0.2 }, max = { 0.4, 0.4 } }, { material = mat })
local function started()
  local f = assert(io.open(mpm.outdir .. "/started", "w"))
  f:close()
end
if mode == "loop" then
  sim:run{ steps = 3 }
  started()
  local x = 0
  while true do x = x + 1 end
elseif mode == "hook" then
  sim:hook{ every_steps = 5, fn = function(s)
    if s:step() < 10 then return end
    started()
    while true do end
  end }
  sim:run{ steps = 1000000 }
elseif mode == "seed" then
  local wide = mpm.simulation{ dim = 2, grid = { size = { 100, 100 }, cell = 0.1 }, thermo = 0, name = "wide",
    diagnostics = false, series = false }
  local ring = mpm.difference(mpm.disk{ center = { 50, 50 }, radius = 49.99 }, mpm.disk{ center = { 50, 50 }, radius = 49.9 })
  started()
  wide:add_particles(ring, { material = mat, per_axis = 8 })
else
  sim:hook{ every_steps = 5, fn = function(s)
    if s:step() < 10 then return end
    started()
    string.rep("a", 15000):find(".-b") -- quadratic in C: about a second
  end }
  sim:run{ steps = 1000000 }
end

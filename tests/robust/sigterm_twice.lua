-- moraine robustness: a run whose every step takes a long while (a slow hook),
-- for tests/robust/sigterm_twice.sh. The file "started" tells the test the
-- run is inside its first hook. The hook is slow inside a C function (a
-- lazy pattern that never matches makes string.find quadratic in the length:
-- tens of seconds), where a signal only sets the flag: Lua code would be
-- stopped by the first signal already (src/lua/lua_interrupt.c).
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, thermo = 0, name = "twice" }
sim:add_particles(mpm.box{ min = { 0.2, 0.2 }, max = { 0.4, 0.4 } }, { material = mat })
sim:hook{ every_steps = 1, fn = function(s)
  local f = assert(io.open(mpm.outdir .. "/started", "w")) f:close()
  string.rep("a", 100000):find(".-b") -- a slow analysis
end }
sim:run{ steps = 100 }

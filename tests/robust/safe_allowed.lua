-- moraine --safe: what a deck may still do (run with --safe; every check
-- raises with its line when it does not hold).
--  - write, append, rename and remove files below the output directory,
--    also through a path whose '..' comes back inside it;
--  - read files anywhere, and load source text with dofile, loadfile,
--    load and require;
--  - debug.traceback, os.getenv, and moraine's own writers and readers:
--    a VTK series in a sub-directory, sim:save and mpm.load, sim:import,
--    moraine.results.write_csv.
local out = mpm.outdir
local function check(cond, what) if not cond then error(what, 2) end end
local function read(path)
  local f = assert(io.open(path, "r"))
  local text = f:read("a")
  f:close()
  return text
end

-- files of the deck's own below the output directory
local f = assert(io.open(out .. "/notes.txt", "w"))
f:write("one\n")
f:close()
f = assert(io.open(out .. "/notes.txt", "a+"))
f:write("two\n")
f:close()
check(read(out .. "/notes.txt") == "one\ntwo\n", "io.open 'w' and 'a+' inside the output directory")
local name = out:match("([^/]+)/*$")
f = assert(io.open(out .. "/../" .. name .. "/back.txt", "w"))
f:close()
check(read(out .. "/back.txt") == "", "a '..' that comes back inside the output directory")
assert(os.rename(out .. "/back.txt", out .. "/moved.txt"))
assert(os.remove(out .. "/moved.txt"))
check(io.open(out .. "/moved.txt") == nil, "os.rename and os.remove inside the output directory")
io.output(out .. "/output.txt")
io.write("via io.output\n")
io.close()
io.output(io.stdout)
check(read(out .. "/output.txt") == "via io.output\n", "io.output inside the output directory")

-- reading anywhere, loading source text
check(read(mpm.deck):find("what a deck may still do", 1, true), "reading the deck itself")
f = assert(io.open(out .. "/module_ok.lua", "w"))
f:write("return { answer = 42 }\n")
f:close()
check(dofile(out .. "/module_ok.lua").answer == 42, "dofile of source text")
check(loadfile(out .. "/module_ok.lua")().answer == 42, "loadfile of source text")
check(load("return x", "=chunk", "t", { x = 7 })() == 7, "load of source text with an environment")
package.path = out .. "/?.lua;" .. package.path
check(require("module_ok").answer == 42, "require of a Lua module")
check(debug.traceback("here"):find("stack traceback", 1, true), "debug.traceback")
check(os.getenv("PATH") ~= nil, "os.getenv")
local ok, err = pcall(os.execute, "true")
check(not ok and err:find("not available with --safe", 1, true), "a refused function raises")

-- moraine's writers and readers
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, thermo = 0, dt = { fixed = 1e-3 },
                            output = { vtk = "series/block", every_steps = 5 } }
sim:add_particles(mpm.box{ min = { 0.2, 0.2 }, max = { 0.4, 0.4 } }, { material = mat })
sim:run{ steps = 10 }
check(read(out .. "/series/block.pvd"):find("block_000002.vtp", 1, true), "a VTK series in a sub-directory")
local saved = sim:save("state.h5")
check(saved == out .. "/state.h5", "sim:save inside the output directory")
local again = mpm.load(saved, { diagnostics = false })
check(again:step() == 10, "mpm.load of the saved state")
local other = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, diagnostics = false }
check(other:import(saved) == sim:particle_count(), "sim:import of the saved state")
require("moraine.results").write_csv("figures.csv", { "a", "b" }, { { 1, 2 } })
check(read(out .. "/figures.csv") == "a,b\n1,2\n", "moraine.results.write_csv")
print("safe_allowed: every allowed operation worked")

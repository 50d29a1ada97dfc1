-- Every output of a 2D and a 3D run read back against the HDF5 checkpoint of
-- the same state (tests/python/check_outputs_roundtrip.py): at each VTK
-- snapshot a hook (at_output) saves a checkpoint, so each .vtp/.vti and the
-- checkpoint beside it hold the same state. Two materials and two registered
-- per-particle fields; at the end each run writes the reductions sim:reduce
-- gives over all particles, a material, a region and a predicate, which the
-- checker recomputes with numpy from the last .vtp.
local soft = mpm.material.linear_elastic{ density = 1200, E = 2e6, nu = 0.25 }
local stiff = mpm.material.linear_elastic{ density = 2000, E = 8e6, nu = 0.3 }

local function run(dim, name)
  local g = dim == 2 and { 0, -9.81 } or { 0, 0, -9.81 }
  local sim = mpm.simulation{ dim = dim, grid = { size = dim == 2 and { 1, 1 } or { 1, 1, 1 }, cell = 0.125 },
                              gravity = g, thermo = 0, diagnostics = false, series = false,
                              output = { vtk = name .. "/p", every_steps = 6, grid = true } }
  local lo, hi = { 0.25, 0.3, 0.3 }, { 0.5, 0.7, 0.7 }
  if dim == 2 then lo[3], hi[3] = nil, nil end
  sim:add_particles(mpm.box{ min = lo, max = hi }, { material = soft,
                    velocity = dim == 2 and { 0.5, 0.2 } or { 0.5, 0.2, -0.1 } })
  lo[1], hi[1] = 0.5, 0.75
  sim:add_particles(mpm.box{ min = lo, max = hi }, { material = stiff })
  sim:particle_field{ name = "damage", unit = "1" }
  sim:particle_field{ name = "marker", components = 3, init = -1 }
  sim:set_field("marker", function(x, y, z, i) return x, y + i, z - i end)
  -- the registered values change during the run, between snapshots
  sim:hook{ every_steps = 4, fn = function(s)
    s:set_field("damage", function(x, y, z, i) return s:time() * (x + 2 * y) + i end)
    s:set_value("marker", 3, { s:step(), -s:step(), 0.5 })
  end }
  local snapshot = 0
  sim:hook{ at_output = true, fn = function(s)
    s:save(string.format("%s/ck_%06d.h5", name, snapshot))
    snapshot = snapshot + 1
  end }
  sim:run{ steps = 18 } -- the last snapshot (step 18) is the final state the reductions see
  assert(snapshot == 4, "expected 4 snapshots (steps 0, 6, 12, 18), got " .. snapshot)

  -- reductions: op, field, options, subset label for the checker
  local upper = dim == 2 and mpm.box{ min = { 0, 0.5 }, max = { 1, 1 } }
                          or mpm.box{ min = { 0, 0.5, 0 }, max = { 1, 1, 1 } }
  local right = function(x, y, z) return x > 0.55 end
  local f = assert(io.open(string.format("%s/%s/reductions.txt", mpm.outdir, name), "w"))
  for _, r in ipairs{
      { "sum", "mass" }, { "max", "x" }, { "min", "y" }, { "mean", "von_mises" }, { "max", "velocity" },
      { "count", "id" }, { "mean", "damage" }, { "max", "marker", { component = 2 } }, { "sum", "marker" },
      { "sum", "mass", { material = stiff }, "material1" }, { "mean", "pressure", { material = soft }, "material0" },
      { "max", "damage", { material = stiff }, "material1" }, { "count", "id", { material = stiff }, "material1" },
      { "mean", "pressure", { region = upper }, "upper" }, { "count", "id", { region = upper }, "upper" },
      { "sum", "damage", { region = upper }, "upper" },
      { "sum", "mass", { where = right }, "right" }, { "min", "eps_D", { where = right }, "right" },
      { "max", "stress", { component = 4, where = right }, "right" },
    } do
    local value = sim:reduce(r[1], r[2], r[3])
    local comp = r[3] and r[3].component or 0
    f:write(string.format("%s %s %d %s %.17g\n", r[1], r[2], comp, r[4] or "all", value))
  end
  f:close()
end

run(2, "run2d")
run(3, "run3d")
print("outputs_roundtrip: wrote the 2D and 3D runs")

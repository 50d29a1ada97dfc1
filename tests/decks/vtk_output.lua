-- VTK output read back by the real VTK reader (tests/python/check_run_vtk.py):
-- a 2D and a 3D run write particle series; at the end each deck dumps its
-- state with sim:field() so the checker can compare the last .vtp with it.
local mat = mpm.material.linear_elastic{ density = 1200, E = 2e6, nu = 0.25 }

local function dump(sim, name)
  local f = assert(io.open(mpm.outdir .. "/" .. name .. ".state", "w"))
  f:write(string.format("count %d\n", sim:particle_count()))
  for _, field in ipairs{ "velocity", "mass", "stress", "id" } do
    local values, ncomp = sim:field(field)
    f:write(field, " ", ncomp)
    for _, v in ipairs(values) do f:write(string.format(" %.17g", v)) end
    f:write("\n")
  end
  f:close()
end

local s2 = mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, gravity = { 0, -9.81 },
                           thermo = 0, diagnostics = false, output = { vtk = "run2d", every_steps = 25 } }
s2:add_particles(mpm.disk{ center = { 0.5, 0.5 }, radius = 0.2 }, { material = mat,
                 velocity = mpm.rigid_rotation{ omega = 2, center = { 0.5, 0.5 } } })
s2:run{ steps = 100 }
dump(s2, "run2d")
-- reductions from Lua, compared by the checker with numpy on the last .vtp
local f = assert(io.open(mpm.outdir .. "/run2d.reductions", "w"))
local upper = mpm.box{ min = { 0, 0.5 }, max = { 1, 1 } }
for _, r in ipairs{ { "max", "x" }, { "min", "y" }, { "sum", "mass" }, { "mean", "von_mises" }, { "max", "velocity" },
                    { "count", "id" }, { "mean", "pressure", { region = upper } },
                    { "sum", "mass", { where = function(x, y) return x < 0.5 end } },
                    { "max", "stress", { component = 4 } } } do
  f:write(string.format("%s %s %s %.17g\n", r[1], r[2], r[3] and (r[3].region and "upper" or r[3].where and "left"
          or "component" .. r[3].component) or "all", s2:reduce(r[1], r[2], r[3])))
end
f:close()

local s3 = mpm.simulation{ dim = 3, grid = { size = { 1, 1, 1 }, cell = 0.125 }, gravity = { 0, 0, -9.81 },
                           thermo = 0, diagnostics = false,
                           output = { vtk = "series3d/run3d", every = 0.002, format = "binary" } }
s3:add_particles(mpm.sphere{ center = { 0.5, 0.5, 0.6 }, radius = 0.25 }, { material = mat, per_axis = 2 })
s3:run{ time = 0.01 }
dump(s3, "series3d/run3d")
print("vtk_output: wrote the 2D and 3D series")

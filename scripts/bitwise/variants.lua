-- Every explicit variant for a few steps, each saved as a checkpoint: the
-- strategies of 000 Table 1 (and MLS) x the four stress updates x the four
-- shape functions x the four face treatments, in 2D and 3D, on a block that
-- touches a friction floor and a slip wall, with Cundall damping. Used by
-- scripts/bitwise/run.sh to show that a change of code leaves every variant
-- bit for bit as it was.
local out = mpm.param("out", ".")
local steps = mpm.param("steps", 40)
local elastic = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sand = mpm.material.mohr_coulomb{ density = 1700, E = 5e6, nu = 0.25, phi = 30, psi = 0, cohesion = 10 }
local strategies = { "PIC", "FLIP", "FLIP0.99", "NFLIP", "APIC", "AFLIP", "TPIC", "TFLIP", "XPIC(2)", "MLS" }
local updates = { "USF", "USL", "MUSL", "USAVG" }
local shapes = { "linear", "gimp", "quadratic_bspline", "cubic_bspline" }
local faces = { "extended", "truncated", "modified", "wls" }

local function block(dim, strategy, update, shape, face, material)
  local size, lo, hi, g = { 0.6, 0.4 }, { 0.0, 0.0 }, { 0.3, 0.2 }, { 2.0, -9.81 }
  if dim == 3 then size, lo, hi, g = { 0.6, 0.3, 0.4 }, { 0.0, 0.0, 0.0 }, { 0.3, 0.15, 0.2 }, { 2.0, 0.5, -9.81 } end
  local sim = mpm.simulation{ dim = dim, grid = { size = size, cell = 0.05 }, gravity = g, shape = shape,
    shape_boundary = face, scheme = { transfer = strategy, stress_update = update }, dt = { cfl = 0.3 },
    damping = { cundall = 0.05 }, boundary = { all = "slip", top = "free", bottom = { "friction", mu = 0.3 } },
    thermo = 0, diagnostics = false }
  local v = dim == 2 and { 0.5, 0.0 } or { 0.5, 0.0, 0.0 }
  sim:add_particles(mpm.box{ min = lo, max = hi }, { material = material, per_axis = 2, velocity = v })
  return sim
end

local function try(label, dim, ...)
  local ok, sim = pcall(block, dim, ...)
  if not ok then print(label .. ": not built: " .. tostring(sim)) return end
  local ran, err = pcall(function() sim:run{ steps = steps } end)
  if not ran then print(label .. ": stopped: " .. tostring(err)) end
  sim:save(string.format("%s/%s.h5", out, label))
end

for _, dim in ipairs{ 2, 3 } do
  for _, strategy in ipairs(strategies) do
    for _, update in ipairs(updates) do
      for _, shape in ipairs(shapes) do
        local label = string.format("d%d_%s_%s_%s", dim, strategy:gsub("[()]", ""), update, shape)
        try(label, dim, strategy, update, shape, "modified", update == "USF" and sand or elastic)
      end
    end
  end
  for _, face in ipairs(faces) do
    for _, shape in ipairs{ "quadratic_bspline", "cubic_bspline" } do
      try(string.format("d%d_faces_%s_%s", dim, face, shape), dim, "FLIP", "USF", shape, face, sand)
    end
  end
end

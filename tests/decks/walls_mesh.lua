-- Rigid walls from closed triangle meshes (shape = "mesh", STL files written
-- here, binary and ASCII), in 3D with quadratic B-splines, elastic blocks
-- (E = 1 MPa, nu = 0.3, rho = 1000 kg/m^3, 8 points per 0.05 m cell):
--   cube: a 12-triangle cube mesh against the equivalent `box` wall, the same
--         particle positions and velocities to round-off (|dx| <= 1e-12 m):
--         a block sliding on the top of a friction box (tilted gravity), a
--         block sliding on the floor of a container (inside = true; the
--         file scaled and moved by scale and translate), a
--         turning, moving plate pushing a block;
--   incline: a thin box tilted by 35 degrees about y (a mesh of 12
--         triangles, no face grid-aligned), mu = 0.3, gravity vertical: a
--         along the plane against g (sin theta - mu cos theta) within 3 %;
--   files: the tilted box from a binary and from an ASCII file, the same
--         results bit for bit;
--   checkpoint: a mesh wall saved and loaded continues bit for bit;
--   tetra: tests/data/tetra_inward.stl (ASCII, its corners wound inward, a
--         path relative to the deck) carries a block on its horizontal top
--         face: the mean force on it over the last 0.1 s of 0.3 s is the
--         weight within 2 %, no particle below the face.
--   --set scheme=APIC (the transfer), --set time=0.6 (the incline's run, s)
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local scheme = mpm.param("scheme", "APIC")
local slide_time = tonumber(mpm.param("time", "0.6"))
local g, cell = 9.81, 0.05
local elastic = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }

-- ---- STL files --------------------------------------------------------------------------

local function f32(x) return (string.unpack("<f", string.pack("<f", x))) end

-- the 12 triangles of the box with corners c[1..8] (c[i] for the bits of
-- i - 1: x, y, z high), counter-clockwise seen from outside
local function box_triangles(c)
  local faces = { { 1, 3, 4, 2 }, { 5, 6, 8, 7 }, { 1, 2, 6, 5 }, { 3, 7, 8, 4 }, { 1, 5, 7, 3 }, { 2, 4, 8, 6 } }
  local tris = {}
  for _, f in ipairs(faces) do
    tris[#tris + 1] = { c[f[1]], c[f[2]], c[f[3]] }
    tris[#tris + 1] = { c[f[1]], c[f[3]], c[f[4]] }
  end
  return tris
end

-- the corners of an axis-aligned box, each mapped by fn (default: as is)
local function corners(lo, hi, fn)
  local c = {}
  for i = 0, 7 do
    local p = { (i & 1) > 0 and hi[1] or lo[1], (i & 2) > 0 and hi[2] or lo[2], (i & 4) > 0 and hi[3] or lo[3] }
    c[i + 1] = fn and fn(p) or p
  end
  return c
end

local function write_binary(path, tris)
  local parts = { string.pack("<c80I4", "binary STL of the walls_mesh deck", #tris) }
  for _, t in ipairs(tris) do
    parts[#parts + 1] = string.pack("<fff fff fff fff I2", 0, 0, 0, t[1][1], t[1][2], t[1][3], t[2][1], t[2][2], t[2][3],
                                    t[3][1], t[3][2], t[3][3], 0)
  end
  local f = assert(io.open(path, "wb"))
  f:write(table.concat(parts))
  f:close()
  return path
end

-- the same numbers as the binary file: its float32 values, printed with the
-- digits that read back as exactly those (ASCII numbers are read as doubles)
local function write_ascii(path, tris)
  local f = assert(io.open(path, "w"))
  f:write("solid walls_mesh\n")
  for _, t in ipairs(tris) do
    f:write("  facet normal 0 0 0\n    outer loop\n")
    for k = 1, 3 do f:write(string.format("      vertex %.17g %.17g %.17g\n", f32(t[k][1]), f32(t[k][2]), f32(t[k][3]))) end
    f:write("    endloop\n  endfacet\n")
  end
  f:write("endsolid walls_mesh\n")
  f:close()
  return path
end

-- ---- the cube against the box -----------------------------------------------------------

local function new_sim(size, gravity)
  return mpm.simulation{ dim = 3, grid = { size = size, cell = cell }, shape = "quadratic_bspline", scheme = scheme,
                         gravity = gravity, boundary = { all = "slip", top = "free" }, dt = { a_tau = 0.2 },
                         diagnostics = false, thermo = 0, progress = false }
end

-- the largest difference of the particles' positions and velocities
local function differ(a, b)
  T.check(a:particle_count() == b:particle_count(), "particle counts differ")
  local dx, dv = 0, 0
  for i = 1, a:particle_count() do
    local p, q = a:particle(i), b:particle(i)
    for d = 1, 3 do
      dx, dv = math.max(dx, math.abs(p.x[d] - q.x[d])), math.max(dv, math.abs(p.v[d] - q.v[d]))
    end
  end
  return dx, dv
end

-- one case twice: the wall as a box and as the cube's mesh; the particles' largest differences
local function cube_case(name, case)
  local runs, moved = {}, {}
  for _, shape in ipairs{ "box", "mesh" } do
    local sim = new_sim(case.size, case.gravity)
    local wall = { name = "w", kind = "friction", mu = 0.3, inside = case.inside, velocity = case.velocity,
                   omega = case.omega }
    if shape == "box" then
      wall.shape, wall.min, wall.max = "box", case.lo, case.hi
    else
      -- with scale and translate, the file holds (x - translate) / scale (exact in binary fractions)
      local k, t = case.scale or 1, case.translate or { 0, 0, 0 }
      local function unplace(q) return { (q[1] - t[1]) / k, (q[2] - t[2]) / k, (q[3] - t[3]) / k } end
      wall.shape, wall.scale, wall.translate = "mesh", case.scale, case.translate
      wall.file = write_binary(mpm.outdir .. "/" .. name .. ".stl", box_triangles(corners(case.lo, case.hi, unplace)))
    end
    sim:add_wall(wall)
    sim:add_particles(mpm.box{ min = case.block[1], max = case.block[2] }, { material = elastic, per_cell = 8 })
    local x0 = sim:diagnostics().center_of_mass
    sim:run{ time = case.time }
    local x1 = sim:diagnostics().center_of_mass
    runs[#runs + 1], moved[#moved + 1] = sim, math.sqrt((x1[1] - x0[1]) ^ 2 + (x1[2] - x0[2]) ^ 2 + (x1[3] - x0[3]) ^ 2)
  end
  T.check(runs[2]:wall("w").contacts > 0, "%s: the mesh wall holds no contact", name)
  T.check(moved[1] > 0.02, "%s: the block moved %.3g m only", name, moved[1])
  local dx, dv = differ(runs[1], runs[2])
  print(string.format("cube %-9s moved %.4f m; mesh - box: |dx| <= %.3g m, |dv| <= %.3g m/s", name, moved[1], dx, dv))
  return dx, dv
end

local th = math.rad(30)
local tilted = { g * math.sin(th), 0, -g * math.cos(th) }
local worst = { dx = 0, dv = 0 }
for name, case in pairs{
  top = { size = { 1.0, 0.5, 0.6 }, gravity = tilted, lo = { -0.5, -0.5, -0.5 }, hi = { 1.5, 1.0, 0.265625 },
          block = { { 0.2, 0.15, 0.27 }, { 0.4, 0.35, 0.37 } }, time = 0.3 },
  container = { size = { 1.0, 0.5, 0.6 }, gravity = tilted, inside = true, lo = { -0.5, -0.5, 0.140625 },
                hi = { 1.5, 1.0, 2.0 }, block = { { 0.2, 0.15, 0.145 }, { 0.4, 0.35, 0.245 } }, time = 0.3,
                scale = 0.5, translate = { 0.25, 0, -0.125 } },
  plate = { size = { 1.0, 0.5, 0.6 }, gravity = { 0, 0, -g }, lo = { 0.625, -0.5, -0.5 }, hi = { 0.75, 1.0, 0.5 },
            velocity = { -0.3, 0, 0 }, omega = { 0, 0, 0.2 }, block = { { 0.35, 0.15, 0.0 }, { 0.55, 0.35, 0.1 } },
            time = 0.4 },
} do
  local dx, dv = cube_case(name, case)
  worst.dx, worst.dv = math.max(worst.dx, dx), math.max(worst.dv, dv)
end
T.expect{ id = "walls_mesh.cube", what = "cube mesh against the box wall: largest |dx|", value = worst.dx, max = 1e-12,
          unit = "m" }

-- ---- the incline ------------------------------------------------------------------------

-- a slab 3 m x 2 m x 0.3 m whose top face passes through p with normal n
local theta = math.rad(35)
local n, t, p = { math.sin(theta), 0, math.cos(theta) }, { math.cos(theta), 0, -math.sin(theta) }, { 0.1, 0, 1.3 }
local function tilt(q) -- q: coordinates along t, y and n from p
  return { p[1] + q[1] * t[1] + q[3] * n[1], q[2], p[3] + q[1] * t[3] + q[3] * n[3] }
end
local slab = box_triangles(corners({ -1.0, -0.75, -0.3 }, { 2.0, 1.25, 0.0 }, tilt))
local binary = write_binary(mpm.outdir .. "/incline.stl", slab)
local ascii = write_ascii(mpm.outdir .. "/incline_ascii.stl", slab)

local function incline(file, time)
  local sim = new_sim({ 2.0, 0.5, 1.6 }, { 0, 0, -g })
  sim:add_wall{ name = "incline", shape = "mesh", file = file, kind = "friction", mu = 0.3 }
  local block = mpm.region(function(x, y, z)
    local s, h = (x - p[1]) * t[1] + (z - p[3]) * t[3], (x - p[1]) * n[1] + (z - p[3]) * n[3]
    return s > 0.2 and s < 0.6 and h > 0 and h < 0.2 and y > 0.15 and y < 0.35
  end)
  sim:add_particles(mpm.box{ min = { 0, 0.15, 0.6 }, max = { 1.0, 0.35, 1.5 } } * block,
                    { material = elastic, per_cell = 8 })
  local c0 = sim:diagnostics().center_of_mass
  sim:run{ time = time }
  local c = sim:diagnostics().center_of_mass
  return sim, (c[1] - c0[1]) * t[1] + (c[3] - c0[3]) * t[3]
end

local a_bin, s = incline(binary, slide_time)
local a_exact = g * (math.sin(theta) - 0.3 * math.cos(theta))
T.expect{ id = "walls_mesh.incline", what = "mesh incline at 35 deg, mu 0.3: |a / a_exact - 1|",
          value = 100 * math.abs(2 * s / slide_time ^ 2 / a_exact - 1), max = 3, unit = "%" }
local b_bin = incline(binary, 0.1)
local b_asc = incline(ascii, 0.1)
local dx, dv = differ(b_bin, b_asc)
T.check(dx == 0 and dv == 0, "binary and ASCII files differ: |dx| %.3g, |dv| %.3g", dx, dv)
print(string.format("incline: a = %.4f m/s^2, closed form %.4f; binary = ASCII bit for bit", 2 * s / slide_time ^ 2,
                    a_exact))

-- ---- checkpoint -------------------------------------------------------------------------

local saved = b_bin:save("walls_mesh.h5")
local again = mpm.load(saved)
again:run{ time = 0.05 }
b_bin:run{ time = 0.05 }
dx, dv = differ(b_bin, again)
T.check(dx == 0 and dv == 0, "a loaded mesh wall differs: |dx| %.3g, |dv| %.3g", dx, dv)
T.check(again:wall("incline").work_friction == b_bin:wall("incline").work_friction, "the wall's friction work differs")
-- ---- a tetrahedron from tests/data, wound inward --------------------------------------

local rest = new_sim({ 1.0, 0.5, 0.6 }, { 0, 0, -g })
rest:add_wall{ name = "tetra", shape = "mesh", file = "../data/tetra_inward.stl", kind = "friction", mu = 0.5 }
rest:add_particles(mpm.box{ min = { 0.3, 0.15, 0.2 }, max = { 0.5, 0.35, 0.3 } }, { material = elastic, per_cell = 8 })
local impulse, span = 0, 0
rest:hook{ every_steps = 1, fn = function(sim)
  if sim:time() > 0.2 then impulse, span = impulse + sim:wall("tetra").force[3] * sim:dt(), span + sim:dt() end
end }
rest:run{ time = 0.3 }
local lowest = math.huge
for i = 1, rest:particle_count() do lowest = math.min(lowest, rest:particle(i).x[3]) end
T.close(-impulse / span, 1000 * 0.004 * g, 0.02, "mean reaction of the tetrahedron's face against the weight")
T.check(lowest > 0.2, "a particle at z = %.4f, below the tetrahedron's face at 0.2", lowest)
print(string.format("tetra: mean reaction %.3f N, weight %.3f N, lowest particle %.4f m", -impulse / span, 4 * g,
                    lowest))
T.done("walls_mesh")

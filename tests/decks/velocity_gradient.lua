-- The particle fields velocity_gradient (L, 9 values row-major, L[3a+b] =
-- dv_a/dx_b) and vorticity (curl v; in 2D the scalar dv/dx - du/dy):
--  * a block in rigid rotation at omega (APIC: the nodal velocities of an
--    affine field are exact, and quadratic B-splines differentiate an affine
--    nodal field exactly) has vorticity 2 omega, in 2D (a scalar) and 3D (a
--    vector along the axis), and L = the rotation's skew matrix;
--  * a block in simple shear v = (gdot y, 0) has L = [[0, gdot], [0, 0]] and
--    vorticity -gdot;
-- after one step (the fields are those of the last step's grid), to
-- round-off. (From the second step on APIC's field departs from the rigid
-- rotation by A^2 dt, A the rotation's skew matrix: the grid momentum of
-- v_p + C (x_i - x_p) is formed at the moved x_p. That is the loss the
-- rotating-cube scaling measures, not an error of the fields.) The same
-- state is written to VTK in every form (binary, zlib + Float32, ascii,
-- VTKHDF) and read back by tests/python/check_velocity_gradient.py with VTK's
-- readers; the fields are not among "all fields" (written when named), which
-- the `all` form checks.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
-- nearly no stiffness: the shear stress of the first stress update would
-- otherwise push the block's edges (E = 1e4 moves L there by 2e-6 1/s)
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e-3, nu = 0.3 }
local omega, gdot = 0.5, 0.2
local tol = 1e-12
local forms = {
  { "bin" }, { "zlib_f32", compress = 6, float32 = true }, { "ascii", format = "ascii" }, { "vtkhdf", format = "vtkhdf" },
  { "all", all = true }, -- no fields named: every built-in field but these two
}

local function block(dim, name, velocity)
  local size = dim == 2 and { 2, 2 } or { 2, 2, 2 }
  local sim = mpm.simulation{ dim = dim, grid = { size = size, cell = 0.1 }, shape = "quadratic_bspline",
                              scheme = { transfer = "APIC", stress_update = "USF" }, dt = { fixed = 1e-4 },
                              boundary = { all = "free" }, thermo = 0, diagnostics = false, series = false }
  local lo, hi = { 0.6, 0.6, 0.6 }, { 1.4, 1.4, 1.4 }
  if dim == 2 then lo[3], hi[3] = nil, nil end
  sim:add_particles(mpm.box{ min = lo, max = hi }, { material = mat, velocity = velocity })
  sim:run{ steps = 1 }
  for _, f in ipairs(forms) do
    sim:output{ vtk = name .. "/" .. f[1], format = f.format or "binary", compress = f.compress or 0,
                float32 = f.float32 or false, fields = f.all and {} or { "id", "velocity_gradient", "vorticity" } }
    sim:write_vtk()
  end
  return sim
end

--- largest |field - expected| over the particles (expected: ncomp numbers)
local function worst(sim, name, expected)
  local v, nc = sim:field(name)
  T.check(nc == #expected, "%s has %d components, expected %d", name, nc, #expected)
  local e = 0
  for i = 1, sim:particle_count() do
    for k = 1, nc do e = math.max(e, math.abs(v[(i - 1) * nc + k] - expected[k])) end
  end
  return e
end

local rot2 = block(2, "rotation2d", mpm.rigid_rotation{ omega = omega, center = { 1, 1 } })
T.expect{ id = "velocity_gradient.rotation2d.vorticity", what = "2D rigid rotation: max |vorticity - 2 omega| (1/s)",
          value = worst(rot2, "vorticity", { 2 * omega }), max = tol }
T.expect{ id = "velocity_gradient.rotation2d.L", what = "2D rigid rotation: max |L - [[0, -omega], [omega, 0]]| (1/s)",
          value = worst(rot2, "velocity_gradient", { 0, -omega, 0, omega, 0, 0, 0, 0, 0 }), max = tol }

local axis = { 1 / 3, 2 / 3, 2 / 3 }
local rot3 = block(3, "rotation3d", mpm.rigid_rotation{ omega = omega, center = { 1, 1, 1 }, axis = axis })
local w = { omega * axis[1], omega * axis[2], omega * axis[3] }
T.expect{ id = "velocity_gradient.rotation3d.vorticity", what = "3D rigid rotation: max |vorticity - 2 omega| (1/s)",
          value = worst(rot3, "vorticity", { 2 * w[1], 2 * w[2], 2 * w[3] }), max = tol }
T.expect{ id = "velocity_gradient.rotation3d.L", what = "3D rigid rotation: max |L - skew(omega)| (1/s)",
          value = worst(rot3, "velocity_gradient", { 0, -w[3], w[2], w[3], 0, -w[1], -w[2], w[1], 0 }),
          max = tol }

local shear = block(2, "shear2d", function(x, y) return { gdot * (y - 1), 0 } end)
T.expect{ id = "velocity_gradient.shear2d.L", what = "2D simple shear: max |L - [[0, gdot], [0, 0]]| (1/s)",
          value = worst(shear, "velocity_gradient", { 0, gdot, 0, 0, 0, 0, 0, 0, 0 }), max = tol }
T.expect{ id = "velocity_gradient.shear2d.vorticity", what = "2D simple shear: max |vorticity + gdot| (1/s)",
          value = worst(shear, "vorticity", { -gdot }), max = tol }

-- a reduction over the field, and the default output leaves it out
local mean = shear:reduce("mean", "vorticity")
T.close(mean, -gdot, 1e-12, "mean vorticity by sim:reduce")
print(string.format("velocity_gradient: omega %.3g, gdot %.3g, %d + %d + %d particles", omega, gdot,
                    rot2:particle_count(), rot3:particle_count(), shear:particle_count()))
T.done("velocity_gradient")

-- The rotating cube of 000 §4.2, shared by rotating_cube.lua and
-- rotating_cube_scaling.lua: a 3 m elastic cube (the bouncing-cube material)
-- thrown in space with V_c = 1.71 cm/s along (1, 1, 1)/sqrt(3) (000, Eq. 49)
-- and omega = 0.108 rad/s along sqrt(2/3) (0.5, 0.5, 1) (000, Eq. 50); 1 m
-- cells, 8 regularly spaced points per cell, no gravity.
local C = { Vc = 0.0171, omega = 0.108 }
local mat = mpm.material.linear_elastic{ density = 1748, E = 12.84e6, nu = 0.16 }
local s3, s23 = 1 / math.sqrt(3), math.sqrt(2 / 3)

--- C.throw{ transfer, shape, a_tau, spin (omega multiplier), size (cells per
-- axis from -2.5 m), diagnostics, diagnostics_every } -> simulation
function C.throw(o)
  local n = o.size or 8
  local sim = mpm.simulation{ dim = 3, grid = { origin = { -2.5, -2.5, -2.5 }, size = { n, n, n }, cell = 1.0 },
                              shape = o.shape or "quadratic_bspline",
                              scheme = { transfer = o.transfer, stress_update = "USF" },
                              boundary = { all = "free" }, dt = { a_tau = o.a_tau or 0.05 }, thermo = 0,
                              diagnostics = o.diagnostics, diagnostics_every = o.diagnostics_every or 100 }
  sim:add_particles(mpm.box{ min = { 0, 0, 0 }, max = { 3, 3, 3 } }, { material = mat, per_axis = 2,
                    placement = "regular",
                    velocity = mpm.rigid_rotation{ omega = C.omega * (o.spin or 1), axis = { 0.5 * s23, 0.5 * s23, s23 },
                                                   center = { 1.5, 1.5, 1.5 },
                                                   velocity = { C.Vc * s3, C.Vc * s3, C.Vc * s3 } } })
  return sim
end

return C

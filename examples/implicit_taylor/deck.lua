-- Taylor bar impact with the implicit energy-momentum consistent integrator
-- (001 §7.4): a copper bar (K = 130 GPa, G = 43.3 GPa, rho = 8930 kg/m^3,
-- von Mises sigma_y = 0.4 GPa, linear hardening H = 0.1 GPa), radius 3.2 mm,
-- length 32.2 mm, hits a rigid frictionless wall at 227 m/s. Quarter model:
-- the symmetry planes x = 0, z = 0 and the wall y = 0 clamp the normal
-- velocity of the grid nodes on them; uGIMP, 0.8 mm cells, 2 points per cell
-- axis, dt = 0.375 us (001 Table 5), ghost stabilisation as in 001 §7.4
-- (`ghost`, default 0.03) and the cells' volumetric averaging against
-- locking (`bbar`, default true; doc/implicit.md, "Volumetric averaging").
-- Nodes lighter than 1 % of a point's mass are left out (`min_node_mass`,
-- default 1e-2: with the integrator's 1e-3 the consistent-mass velocity
-- projection reaches 1e8 m/s at fringe nodes and its round-off costs the
-- energy balance 1e-9; doc/implicit.md, "Small nodes"). Newton is given 6
-- iterations (`max_iter`); a step that needs more is tried again with half
-- the time step (`cutbacks`, default 4; doc/implicit.md, "Cutbacks").
-- Prints each step's Newton history and the energy balance, the final length
-- and mushroom radius; writes the particles at the end. Run by
-- tests/decks/implicit_taylor.lua, which checks the figures it returns.
--
--   moraine examples/implicit_taylor/deck.lua -o out/taylor --set time=20e-6
local quick = mpm.param("quick", false)
local tend = mpm.param("time", quick and 0.3e-6 or 80e-6)
local verbose = mpm.param("verbose", true)
local K, G = 130e9, 43.3e9
local E, nu = 9 * K * G / (3 * K + G), (3 * K - 2 * G) / (2 * (3 * K + G))
local r0, h0, v0, h = 3.2e-3, mpm.param("length", 32.2e-3), 227.0, 0.8e-3
local copper = mpm.material.von_mises{ density = 8930, E = E, nu = nu, yield = 0.4e9, hardening = 0.1e9 }
local sim = mpm.simulation{ dim = 3, grid = { origin = { -2 * h, -2 * h, -2 * h }, size = { 11 * h, 45 * h, 11 * h }, cell = h },
                            shape = "gimp", thermo = 0, diagnostics = false, series = false,
                            output = { vtk = "taylor", every = 1 } }
local quarter = mpm.intersection(mpm.cylinder{ from = { 0, 0, 0 }, to = { 0, h0, 0 }, radius = r0 },
                                 mpm.box{ min = { 0, 0, 0 }, max = { r0, h0, r0 } })
sim:add_particles(quarter, { material = copper, per_axis = 2, velocity = { 0, -v0, 0 } })
local far = 1
sim:constrain{ region = mpm.box{ min = { -far, -far, -far }, max = { 1e-9, far, far } }, vx = 0 }
sim:constrain{ region = mpm.box{ min = { -far, -far, -far }, max = { far, far, 1e-9 } }, vz = 0 }
sim:constrain{ region = mpm.box{ min = { -far, -far, -far }, max = { far, 1e-9, far } }, vy = 0 }
local imp = sim:implicit{ mass = "consistent", mapping = "FLIP", tol = 1e-11, dt = mpm.param("dt", 0.375e-6),
                          max_iter = mpm.param("max_iter", 6), cutbacks = mpm.param("cutbacks", 4),
                          ghost = mpm.param("ghost", 0.03), min_node_mass = mpm.param("min_node_mass", 1e-2),
                          bbar = mpm.param("bbar", true) }

-- Length and mushroom radius, from the convected particle domains (each
-- point's initial cube of side h/2 mapped by its F):
--   length: the largest y reached by a domain, y_p + (h/4) sum_j |F_yj|;
--   radius: the impact face's area-equivalent radius sqrt(4 A / pi), A the
--     x-z projected area of the wall-side faces of the first layer of points
--     (initial y below h/2), (h/2)^2 cof(F)_yy each;
--   radius_max: the largest radial extent of those domains,
--     r_p + (h/4) sum_j |(F^T e_r)_j|.
local function shape()
  local F = sim:field("deformation_gradient")
  local u = sim:field("displacement")
  local length, area, rmax = 0, 0, 0
  for i = 1, sim:particle_count() do
    local px, py, pz = table.unpack(sim:particle(i).x)
    local f = function(a, b) return F[(i - 1) * 9 + 3 * (a - 1) + b] end
    length = math.max(length, py + h / 4 * (math.abs(f(2, 1)) + math.abs(f(2, 2)) + math.abs(f(2, 3))))
    if py - u[3 * (i - 1) + 2] < h / 2 then
      area = area + (h / 2) ^ 2 * (f(3, 3) * f(1, 1) - f(3, 1) * f(1, 3))
      local r = math.sqrt(px * px + pz * pz)
      local er = 0
      for b = 1, 3 do er = er + math.abs((px * f(1, b) + pz * f(3, b)) / r) end
      rmax = math.max(rmax, r + h / 4 * er)
    end
  end
  return { length = length, radius = math.sqrt(4 * area / math.pi), radius_max = rmax }
end

local s0, e0 = shape(), imp:energy()
print(string.format("%d points, initial kinetic energy %.4g J (quarter bar)", sim:particle_count(), e0.kinetic))
-- what the run returns (tests/decks/implicit_taylor.lua checks it)
local run = { steps = 0, max_iterations = 0, over_six = 0, worst_final = 0, worst_rate = 0, drift = 0, e0 = e0,
              s0 = s0, cut_steps = 0, cuts = 0, rejected_iterations = 0 }
while sim:time() < tend - 1e-12 do
  local step = imp:step()
  local e = imp:energy()
  local n = step.iterations
  run.steps = run.steps + 1
  run.max_iterations = math.max(run.max_iterations, n)
  if n > 6 then run.over_six = run.over_six + 1 end
  if step.cuts > 0 then run.cut_steps = run.cut_steps + 1 end
  run.cuts, run.rejected_iterations = run.cuts + step.cuts, run.rejected_iterations + step.rejected_iterations
  if n >= 1 then run.worst_final = math.max(run.worst_final, step.errors[n]) end
  -- the last iteration's reduction of the error measure: quadratic convergence near the solution
  if n >= 3 then run.worst_rate = math.max(run.worst_rate, step.errors[n] / step.errors[n - 1]) end
  run.drift = math.max(run.drift, math.abs(e.total - e0.total) / e0.total)
  if verbose then
    local errs = {}
    for k, v in ipairs(step.errors) do errs[k] = string.format("%.1e", v) end
    local cut = step.cuts > 0 and string.format("  (dt %.4g us after %d cut%s, %d iterations rejected)", 1e6 * step.dt,
                                                step.cuts, step.cuts > 1 and "s" or "", step.rejected_iterations) or ""
    print(string.format("t = %.4e s  %2d iterations [%s]  max|r| %.1e N  dissipated %.4g J  ghost %.3g J  "
                        .. "energy change %.2e%s", sim:time(), n, table.concat(errs, " "), step.residual, e.dissipated,
                        e.ghost, math.abs(e.total - e0.total) / e0.total, cut))
  end
end
run.e, run.s, run.time = imp:energy(), shape(), sim:time()
print(string.format("%d steps to t = %.4g us: Newton <= %d iterations (%d steps > 6; %d steps cut back %d times, "
                    .. "%d iterations rejected), kinetic %.4g J, plastic %.4g J, ghost %.4g J of %.4g J; "
                    .. "kinetic + stored + plastic + ghost constant to %.2e", run.steps, 1e6 * sim:time(),
                    run.max_iterations, run.over_six, run.cut_steps, run.cuts, run.rejected_iterations, run.e.kinetic,
                    run.e.dissipated, run.e.ghost, e0.total, run.drift))
print(string.format("length %.4f -> %.4f mm (ratio %.4f), mushroom radius (area) %.4f -> %.4f mm (ratio %.4f), "
                    .. "(largest) %.4f -> %.4f mm (ratio %.4f)", 1e3 * s0.length, 1e3 * run.s.length,
                    run.s.length / s0.length, 1e3 * s0.radius, 1e3 * run.s.radius, run.s.radius / s0.radius,
                    1e3 * s0.radius_max, 1e3 * run.s.radius_max, run.s.radius_max / s0.radius_max))
sim:write_vtk()
return run

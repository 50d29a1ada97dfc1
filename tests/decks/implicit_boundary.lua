-- Face conditions and prescribed velocities in the implicit integrator:
-- uniaxial compression of an elastic (Hencky) block, 1 m x 1 m, between slip
-- walls (the default face condition on the grid faces x = 0 and x = 1 and the
-- floor y = 0), pushed down by a plate of prescribed velocity
-- (sim:constrain{ vy = -v } on the nodes of its top surface), 1 % in 1 s
-- (the plate is a line of grid nodes: it holds the material only while the
-- block's top stays in the cell below it).
--   1. the slip walls confine it laterally: uniaxial strain, whose Hencky
--      stress is tau_yy = (lambda + 2 G) ln(l), sigma_yy = tau_yy / l for the
--      stretch l = 1 - v t (a block free to bulge would carry the uniaxial
--      stress E ln(l) / l, 26 % less): the mean sigma_yy of the points
--      within 2 % of it (the plate starts suddenly: the stress waves it
--      sends are rho c v = 2.7 % of the final stress);
--   2. the wall nodes keep their normal displacement zero: no point leaves
--      the block's width, the floor's points stay on it;
--   3. the plate's work is booked (imp:energy().constraint_work, and in
--      W_external of the diagnostics): kinetic + stored - plate work constant
--      to 1e-9 of the plate work; W_MPM likewise;
--   4. Newton converges on every step (final ratio <= 1e-10, <= 6 iterations).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local E, nu, rho, v = 1e6, 0.3, 1000, 0.01
local lambda, G = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
local mat = mpm.material.hencky{ density = rho, E = E, nu = nu }
local sim = mpm.simulation{ dim = 2, grid = { size = { 1, 1.5 }, cell = 0.1 }, shape = "linear", thermo = 0,
                            diagnostics = false, series = false, boundary = { all = "slip", top = "free" },
                            integrator = "implicit", implicit = { dt = 0.01, mapping = "FLIP" } }
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 1, 1 } }, { material = mat, per_axis = 2 })
sim:constrain{ region = mpm.box{ min = { -1, 1 - 1e-9 }, max = { 2, 1 + 1e-9 } }, vy = -v }
local imp = sim:integrator()
local function extents()
  local x0, x1, y0 = math.huge, -math.huge, math.huge
  for i = 1, sim:particle_count() do
    local x = sim:particle(i).x
    x0, x1, y0 = math.min(x0, x[1]), math.max(x1, x[1]), math.min(y0, x[2])
  end
  return x0, x1, y0
end
local xmin0, xmax0, ymin0 = extents()
local most, worst = 0, 0
sim:hook{ every_steps = 1, fn = function(s)
  if s:step() == 0 then return end
  local h = imp:last()
  most = math.max(most, h.iterations)
  if h.iterations > 0 then worst = math.max(worst, h.errors[h.iterations]) end
end }
sim:run{ time = 1 }

local l = 1 - v * sim:time()
local sigma_ref = (lambda + 2 * G) * math.log(l) / l
local syy, n = 0, sim:particle_count()
local stress = sim:field("stress")
for i = 1, n do syy = syy + stress[(i - 1) * 6 + 2] / n end
local xmin, xmax, ymin = extents()
T.expect{ id = "implicit_boundary.sigma_yy", what = "mean sigma_yy under the plate, uniaxial strain (Hencky)",
          value = syy, reference = sigma_ref, rtol = 0.02 }
T.check(math.abs(xmin - xmin0) < 1e-12 and math.abs(xmax - xmax0) < 1e-12,
        "points moved sideways at a slip wall: x in [%.15g, %.15g], was [%.15g, %.15g]", xmin, xmax, xmin0, xmax0)
T.check(ymin < ymin0 and ymin > ymin0 * (1 - 3 * v), "the lowest points at y = %g (start %g): not held by the floor",
        ymin, ymin0)
local e = imp:energy()
T.check(e.constraint_work > 0, "the plate did no work (%g)", e.constraint_work)
T.expect{ id = "implicit_boundary.energy", what = "kinetic + stored - plate work / plate work",
          value = math.abs(e.kinetic + e.strain - e.constraint_work) / e.constraint_work, max = 1e-9 }
local d = sim:energy()
T.expect{ id = "implicit_boundary.W_MPM", what = "|W_MPM| / plate work (diagnostics)",
          value = math.abs(d.mpm_error) / e.constraint_work, max = 1e-9 }
T.check(most <= 6 and worst <= 1e-10, "Newton: %d iterations at most, final ratio %.3g", most, worst)
print(string.format("implicit_boundary: sigma_yy %.6g Pa (uniaxial strain %.6g, uniaxial stress %.6g), plate work "
                    .. "%.6g J/m, energy error %.3g, Newton <= %d", syy, sigma_ref, E * math.log(l) / l,
                    e.constraint_work, math.abs(e.kinetic + e.strain - e.constraint_work) / e.constraint_work, most))
T.done("implicit_boundary")

-- A block sliding on another block: contact between bodies with Coulomb
-- friction (solver/contact.h) against the closed form. The lower block
-- (2 m x 0.2 m) rests on a fixed floor; the upper one (0.4 m x 0.2 m) sits
-- on it, both elastic (E = 10 MPa, nu = 0.3, rho = 1000 kg/m^3), under
-- gravity tilted by theta = 30 degrees along the blocks. With mu = 0.3 the
-- upper block slides down at a = g (sin theta - mu cos theta); with
-- mu >= tan theta it sticks (relative acceleration below 3 % of g sin theta). The work of friction W_contact equals
-- -mu N times the distance slid (N = m g cos theta), and W_MPM stays small.
-- The relative velocity is sampled every `sample` seconds from t1 to t1 + t2
-- and a is its least-squares slope: the sudden load sets the lower block
-- vibrating in shear (period 4 H / c_s, about 13 ms), which the PIC-like
-- updates damp and FLIP keeps, so the velocity difference of two instants would carry the
-- vibration's phase. The distance slid is the trapezoidal sum of the samples.
-- With theta = 0 the block settles (damped) on the other and keeps its
-- lithostatic mean stress (less an error of the cell size, from the contact
-- rows inside the block: --set cell=0.025 makes the block 8 cells high).
-- With --set given_normal=false the contact takes the mass-gradient normal,
-- which catches the block at its front (doc/numerics.md, "Contact between
-- bodies"): it does not slide, and the checks fail.
--   moraine tests/decks/contact_slide.lua [--set mu=0.7] [--set transfer=APIC] [--set cell=0.025]
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local mu = mpm.param("mu", 0.3)
local theta = math.rad(mpm.param("theta", 30))
local transfer = mpm.param("transfer", "FLIP")
local g = 10
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e7, nu = 0.3 }

local sim = mpm.simulation{
  dim = 2, grid = { origin = { 0, 0 }, size = { 2.4, 0.6 }, cell = mpm.param("cell", 0.05) }, shape = "quadratic_bspline",
  scheme = { transfer = transfer, stress_update = mpm.param("stress_update", "USF") },
  boundary = { all = "free", ymin = "fixed" }, gravity = { g * math.sin(theta), -g * math.cos(theta) },
  dt = { cfl = 0.4 }, thermo = 0, diagnostics = false,
}
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 2, 0.2 } }, { material = mat, body = "floor" })
sim:add_particles(mpm.box{ min = { 0.2, 0.2 }, max = { 0.6, 0.4 } }, { material = mat, body = "block" })
-- the interface's normal given (the default), or the mass-gradient normal (--set given_normal=false)
local normal = mpm.param("given_normal", true) and { 0, 1 } or nil
sim:add_contact{ bodies = { "floor", "block" }, kind = mpm.param("kind", "friction"), mu = mu, normal = normal }
-- at rest: Cundall's damping (000 uses 0.1 for settling) takes out the waves of the sudden load
if mpm.param("theta", 30) == 0 then sim:set_damping{ cundall = 0.1 } end

-- the upper block's mean x velocity and position, and the lower block's
-- mean x velocity
local function state()
  local v, m, b = sim:field("velocity"), sim:field("mass"), sim:field("body")
  local s = { 0, 0, 0, 0 }
  for i = 1, #m do
    local k = b[i] == 2 and 1 or 3
    s[k] = s[k] + m[i] * v[3 * i - 2]
    s[k + 1] = s[k + 1] + m[i]
  end
  return s[1] / s[2], s[3] / s[4], s[2]
end

sim:run{ time = mpm.param("t1", 0.1) }
local W1 = sim:diagnostics().W_contact
local ts, vs = {}, {}
local function sample()
  local v, w = state()
  ts[#ts + 1], vs[#vs + 1] = sim:time(), v - w
end
sample()
local sample_dt, t2 = mpm.param("sample", 0.005), mpm.param("t2", 0.3)
for _ = 1, math.floor(t2 / sample_dt + 0.5) do
  sim:run{ time = sample_dt }
  sample()
end
local d, m = sim:diagnostics(), select(3, state())
local a = T.slope(ts, vs)
local expected = math.max(0, g * (math.sin(theta) - mu * math.cos(theta)))
-- the friction work over the samples: mu N times the relative distance slid
local slid = 0
for k = 2, #ts do slid = slid + 0.5 * (vs[k] + vs[k - 1]) * (ts[k] - ts[k - 1]) end
local W = d.W_contact - W1
print(string.format("contact_slide (%s, mu = %g, theta = %g deg): relative acceleration %.4f m/s^2, "
                    .. "expected %.4f; W_contact %.4g J/m over the slide, -mu N s = %.4g; W_MPM %.3g J/m, "
                    .. "E_total %.4g J/m", transfer, mu, math.deg(theta), a, expected, W,
                    -mu * m * g * math.cos(theta) * slid, d.W_MPM, d.E_total))
-- the upper block's mean vertical stress, against the lithostatic -rho g cos(theta) H / 2
local function mean_syy()
  local s, b, m = sim:field("stress"), sim:field("body"), sim:field("mass")
  local sum, M = 0, 0
  for i = 1, #m do
    if b[i] == 2 then sum, M = sum + m[i] * s[6 * i - 4], M + m[i] end
  end
  return sum / M
end
if mpm.param("theta", 30) == 0 then
  local syy, ref = mean_syy(), -1000 * g * 0.2 / 2
  print(string.format("contact_slide at rest: mean sigma_yy of the upper block %.1f Pa, lithostatic %.1f Pa", syy, ref))
  T.close(syy, ref, 0.03, "mean vertical stress of the block resting on the other")
elseif expected > 0 then
  T.close(a, expected, 0.03, "relative acceleration of the sliding block")
  T.close(W, -mu * m * g * math.cos(theta) * slid, 0.05, "W_contact over the slide", 1e-9)
else
  -- the block settles onto the other with some slip before the normal force builds up; then it sticks
  T.check(math.abs(a) < 0.03 * g * math.sin(theta), "the block should stick (mu >= tan theta): relative "
          .. "acceleration %g m/s^2", a)
end

-- An elastic disk let go on an inclined rigid plane (2D plane strain).
--
-- The plane is a wall (`sim:add_wall{shape = "plane"}`) at `theta` to the
-- grid, with Coulomb friction; gravity is vertical. A disk released from
-- rest rolls without slipping, with its centre at a = (2/3) g sin(theta),
-- when mu >= tan(theta) / 3, and slides at a = g (sin(theta) - mu cos(theta))
-- below that (a rigid disk; an elastic one this stiff is within a fraction of
-- a percent of it). The deck runs one disk per value of mu, records the
-- centre's distance along the plane, fits s = s0 + v0 t + a t^2 / 2 and
-- compares a with the closed form. `gap_check` releases the contact where
-- the material stands clear of the wall (doc/numerics.md, "Rolling").
--
-- Parameters (--set key=value): theta (30 deg), mus (0.5,0.1), cells (cells
-- per radius, 8), per_cell (particles per cell, 4: 2 x 2; 9: 3 x 3),
-- strategy (APIC), time (0.6 s), gap_check (true), quick
-- (true: 4 cells per radius, 0.2 s, what ctest runs). Writes `disk_mu<mu>.csv`
-- (t, s, the closed form's s, the spin omega), `disk_mu<mu>_final.csv` (the
-- particles: x, y, speed) and `summary.csv`; plot.py draws them.
local quick = mpm.param("quick", false)
local theta = math.rad(mpm.param("theta", 30))
local cells = mpm.param("cells", quick and 4 or 8)
local strategy = mpm.param("strategy", "APIC")
local per_cell = mpm.param("per_cell", 4)
local duration = mpm.param("time", quick and 0.2 or 0.6)
local gap_check = mpm.param("gap_check", true)
local mus = {}
for m in tostring(mpm.param("mus", "0.5,0.1")):gmatch("[^,]+") do
  mus[#mus + 1] = assert(tonumber(m), "mus: numbers, comma-separated")
end

local g, R, rho = 9.81, 0.1, 1000
local rubber = mpm.material.linear_elastic{ density = rho, E = 1e7, nu = 0.3 }
local n = { math.sin(theta), math.cos(theta) }  -- the plane's normal, out of the wall
local t = { math.cos(theta), -math.sin(theta) } -- down the plane
local p0 = { 0.05, 0.75 }                       -- a point of the plane

-- the closed form's acceleration along the plane
local function closed_form(mu)
  if mu >= math.tan(theta) / 3 then return 2 / 3 * g * math.sin(theta), "rolls" end
  return g * (math.sin(theta) - mu * math.cos(theta)), "slides"
end

-- least squares s = s0 + v0 t + a t^2 / 2 over the samples; returns a
local function fitted_acceleration(ts, ss)
  local S, b = { 0, 0, 0, 0, 0 }, { 0, 0, 0 }
  for i = 1, #ts do
    for k = 0, 4 do S[k + 1] = S[k + 1] + ts[i] ^ k end
    for k = 0, 2 do b[k + 1] = b[k + 1] + ss[i] * ts[i] ^ k end
  end
  local function det(m)
    return m[1][1] * (m[2][2] * m[3][3] - m[2][3] * m[3][2]) - m[1][2] * (m[2][1] * m[3][3] - m[2][3] * m[3][1]) +
             m[1][3] * (m[2][1] * m[3][2] - m[2][2] * m[3][1])
  end
  return 2 * det{ { S[1], S[2], b[1] }, { S[2], S[3], b[2] }, { S[3], S[4], b[3] } } /
           det{ { S[1], S[2], S[3] }, { S[2], S[3], S[4] }, { S[3], S[4], S[5] } }
end

local function roll(mu)
  local sim = mpm.simulation{ dim = 2, grid = { size = { 1.0, 0.9 }, cell = R / cells }, shape = "quadratic_bspline",
    scheme = strategy, gravity = { 0, -g }, dt = { a_tau = 0.2 }, thermo = 0, diagnostics = false,
    boundary = { all = "slip", top = "free" } }
  sim:add_wall{ name = "incline", shape = "plane", point = p0, normal = n, kind = "friction", mu = mu,
                gap_check = gap_check }
  local c0 = { p0[1] + 0.12 * t[1] + R * n[1], p0[2] + 0.12 * t[2] + R * n[2] }
  sim:add_particles(mpm.disk{ center = c0, radius = R }, { material = rubber, per_cell = per_cell })
  local a_exact, how = closed_form(mu)
  local name = string.format("disk_mu%g", mu):gsub("%.", "p")
  local f = assert(io.open(mpm.outdir .. "/" .. name .. ".csv", "w"))
  f:write("time,s,s_closed_form,omega\n")
  local ts, ss = {}, {}
  for _ = 1, 30 do
    sim:run{ time = duration / 30 }
    local d = sim:diagnostics()
    local c = d.center_of_mass
    local s = (c[1] - c0[1]) * t[1] + (c[2] - c0[2]) * t[2]
    -- the spin from the angular momentum about the centre: L_c = I omega, I = m R^2 / 2
    local omega = d.L_centroid / (0.5 * d.mass * R * R)
    ts[#ts + 1], ss[#ss + 1] = sim:time(), s
    f:write(string.format("%.6g,%.6g,%.6g,%.6g\n", sim:time(), s, 0.5 * a_exact * sim:time() ^ 2, omega))
  end
  f:close()
  local out = assert(io.open(mpm.outdir .. "/" .. name .. "_final.csv", "w"))
  out:write("x,y,speed\n")
  -- every particle of the run, on any number of processes
  local pos, vel = sim:field("position", { gather = true }), sim:field("velocity", { gather = true })
  for i = 1, #pos // 3 do
    out:write(string.format("%.6g,%.6g,%.6g\n", pos[3 * i - 2], pos[3 * i - 1],
                            math.sqrt(vel[3 * i - 2] ^ 2 + vel[3 * i - 1] ^ 2)))
  end
  out:close()
  local W_MPM = sim:diagnostics().W_MPM
  sim:free()
  return fitted_acceleration(ts, ss), a_exact, how, W_MPM
end

local summary = assert(io.open(mpm.outdir .. "/summary.csv", "w"))
summary:write("mu,motion,a,a_closed_form,deviation_percent,W_MPM\n")
print(string.format("disk on a %g degree wall, %d cells per radius, %d particles per cell, %s, gap_check %s:",
                    math.deg(theta), cells, per_cell, strategy, tostring(gap_check)))
for _, mu in ipairs(mus) do
  local a, exact, how, W_MPM = roll(mu)
  local dev = 100 * (a / exact - 1)
  summary:write(string.format("%g,%s,%.6g,%.6g,%.4g,%.6g\n", mu, how, a, exact, dev, W_MPM))
  print(string.format("  mu %g (%s): a = %.4f m/s^2, closed form %.4f (%+.1f %%), W_MPM %.3g J/m", mu, how, a, exact,
                      dev, W_MPM))
end
summary:close()

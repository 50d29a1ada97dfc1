-- probe: a disk on an inclined friction plane
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local g, rho, E = 9.81, 1000, tonumber(mpm.param("E", "1e7"))
local R = 0.1
local cells = tonumber(mpm.param("cells", "8"))
local theta = tonumber(mpm.param("theta", "30"))
local mu = tonumber(mpm.param("mu", "0.5"))
local strategy = mpm.param("strategy", "FLIP")
local time = tonumber(mpm.param("time", "0.3"))
local kind = mpm.param("kind", "wall")
local cell = R / cells
local th = math.rad(theta)

local n, t = { math.sin(th), math.cos(th) }, { math.cos(th), -math.sin(th) }
local sim, c0
if kind == "wall" then
  local p = { 0.05, 0.75 }
  sim = mpm.simulation{ dim = 2, grid = { size = { 1.0, 0.9 }, cell = cell }, shape = "quadratic_bspline",
                        scheme = strategy, gravity = { 0, -g }, boundary = { all = "slip", top = "free" },
                        dt = { a_tau = 0.2 }, diagnostics = false, thermo = 0, progress = false }
  sim:add_wall{ name = "incline", shape = "plane", point = p, normal = n, kind = "friction", mu = mu }
  c0 = { p[1] + 0.12 * t[1] + R * n[1], p[2] + 0.12 * t[2] + R * n[2] }
else
  n, t = { 0, 1 }, { 1, 0 }
  sim = mpm.simulation{ dim = 2, grid = { size = { 1.0, 0.3 }, cell = cell }, shape = "quadratic_bspline",
                        scheme = strategy, gravity = { g * math.sin(th), -g * math.cos(th) },
                        boundary = { all = "slip", top = "free", bottom = { "friction", mu = mu } },
                        dt = { a_tau = 0.2 }, diagnostics = false, thermo = 0, progress = false }
  c0 = { 0.15, R }
end
sim:add_particles(mpm.disk{ center = c0, radius = R },
                  { material = mpm.material.linear_elastic{ density = rho, E = E, nu = 0.3 }, per_cell = tonumber(mpm.param("ppc", "4")) })

local function state()
  local d = sim:diagnostics()
  local c = d.center_of_mass
  local Lz, I = 0, 0
  for i = 1, sim:particle_count() do
    local q = sim:particle(i)
    local rx, ry = q.x[1] - c[1], q.x[2] - c[2]
    Lz = Lz + q.mass * (rx * q.v[2] - ry * q.v[1])
    I = I + q.mass * (rx * rx + ry * ry)
  end
  gmin = 1e9
  if kind == "wall" then
    for i = 1, sim:particle_count() do
      local q = sim:particle(i)
      gmin = math.min(gmin, (q.x[1] - 0.05) * n[1] + (q.x[2] - 0.75) * n[2] - 0.25 * cell)
    end
  end
  local v = d.momentum[1] / d.mass * t[1] + d.momentum[2] / d.mass * t[2]
  return (c[1] - c0[1]) * t[1] + (c[2] - c0[2]) * t[2], v, -Lz / I, (c[1] - c0[1]) * n[1] + (c[2] - c0[2]) * n[2]
end

-- least squares s = s0 + v0 t + a t^2 / 2 over samples after 0.05 s
local ts, ss = {}, {}
local nsamp = tonumber(mpm.param("samples", "20"))
local hop = 0
for k = 1, nsamp do
  sim:run{ time = time / nsamp }
  local s, v, w, h = state()
  hop = math.max(hop, h)
  ts[#ts + 1], ss[#ss + 1] = sim:time(), s
  if mpm.param("trace", "0") == "1" then print(string.format("t %.3f s %.5f v %.4f omega R %.4f slip %.4f h %.5f gmin %.5f contacts %d", sim:time(), s, v, w * R, v - w * R, h, gmin, kind == "wall" and sim:wall("incline").contacts or 0)) end
end
-- fit
local S = { 0, 0, 0, 0, 0 }
local b = { 0, 0, 0 }
for i = 1, #ts do
  local x = ts[i]
  for k = 0, 4 do S[k + 1] = S[k + 1] + x ^ k end
  for k = 0, 2 do b[k + 1] = b[k + 1] + ss[i] * x ^ k end
end
local A = { { S[1], S[2], S[3] }, { S[2], S[3], S[4] }, { S[3], S[4], S[5] } }
local function det(M)
  return M[1][1] * (M[2][2] * M[3][3] - M[2][3] * M[3][2]) - M[1][2] * (M[2][1] * M[3][3] - M[2][3] * M[3][1]) +
           M[1][3] * (M[2][1] * M[3][2] - M[2][2] * M[3][1])
end
local D = det(A)
local A3 = { { A[1][1], A[1][2], b[1] }, { A[2][1], A[2][2], b[2] }, { A[3][1], A[3][2], b[3] } }
local a = 2 * det(A3) / D
local roll = 2 / 3 * g * math.sin(th)
local slide = g * (math.sin(th) - mu * math.cos(th))
print(string.format("hop %.2e m; %s %s cells %g theta %g mu %g: a = %.4f, rolling %.4f (%.1f %%), sliding %.4f (%.1f %%)", hop, kind,
                    strategy, cells, theta, mu, a, roll, 100 * (a / roll - 1), slide, 100 * (a / slide - 1)))

-- Plane Poiseuille start-up flow (004 §3.1; series solution of Morris, Fox &
-- Zhu 1997): a Newtonian fluid at rest between two no-slip plates y = 0 and
-- y = H, periodic along x, is driven from t = 0 by a body force F along x
-- (gravity = {F, 0}). The exact profile is
--   u(y, t) = F/(2 nu) y (H - y)
--           - sum_{n odd} 4 F H^2 / (nu pi^3 n^3) sin(n pi y / H) exp(-n^2 pi^2 nu t / H^2).
-- 004's data in SI: H = 5 mm, F = 10 m/s^2, rho = 1000 kg/m^3, mu = 0.5 Pa s
-- (nu = 5e-4 m^2/s, diffusion time T = H^2/nu = 0.05 s, centreline speed at
-- rest 0.0625 m/s), bulk modulus 1.4e5 Pa (c = 11.8 m/s: Mach 0.005; the flow
-- u(y) is divergence-free, so the pressure stays uniform). Quadratic
-- B-splines with the WLS kernel correction at the plates, 2 x 2 particles per
-- cell, a slab 4 cells wide, time step cfl = 0.5 (where the viscous limit
-- h^2/nu of 002 Eq. 36 governs, on the finest grids, cfl = 1 is unstable:
-- N = 128 blows up).
--
-- Error norm: at each time t the particle error e_p = u_p - u(y_p, t), with
--   e_max(t) = max_p |e_p| / u(H/2, t),   e_rms(t) = sqrt(mean_p e_p^2) / u(H/2, t),
-- and for the convergence order E(h) = sqrt(mean over the three times of
-- e_rms^2), the order being the least-squares slope of log E against log h.
-- (004 Eq. 18 divides the root of the sum of squares by the particle count N,
-- which for its N x N lattice adds one to the measured order; the RMS used
-- here does not.)
--
-- Asserts (issue 4 item 3): APIC at the finest resolution within 2 % (e_max)
-- of the series at t/T = 0.05, 0.15, 0.5; APIC order over the resolutions
-- >= 1.7. The FLIP/PIC blend FLIP0.99 (004's "MPM with 1 % PIC") is reported.
-- Quick (N = 8, 16, 32, 64 cells across H, ~6 s): APIC e_max at N = 64 is
-- 0.045 %, 0.020 %, 0.014 %, order 2.83; FLIP0.99 e_max at N = 64 is 0.29 %,
-- 0.49 %, 0.83 %, order 0.87. Full (`--set full=true`, adds N = 128, ~25 s):
-- APIC e_max 0.007 %, 0.003 %, 0.003 %, order 3.14; FLIP0.99 order 0.86
-- (004: 2 and 1, with its norm).
-- `--set boundary=extended` (ghost nodes instead of the WLS correction) shows
-- APIC stalling at e_max ~1-1.7 % from N = 16 to 128 (order ~0): not asserted.
-- Parameters: full, cells (list, e.g. 8,16,32), transfers (list), boundary, cfl.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local full = mpm.param("full", false)
local H, F, rho, mu, K = 5e-3, 10.0, 1000.0, 0.5, 1.4e5
local nu = mu / rho
local Tdiff = H * H / nu
local c = math.sqrt(K / rho)
local cfl = mpm.param("cfl", 0.5)
local function list(s)
  local t = {}
  for w in s:gmatch("[^,]+") do t[#t + 1] = tonumber(w) or w end
  return t
end
local resolutions = list(mpm.param("cells", full and "8,16,32,64,128" or "8,16,32,64"))
local transfers = list(mpm.param("transfers", "APIC,FLIP0.99"))
local fractions = { 0.05, 0.15, 0.5 }

local function series(y, t)
  local u = F / (2 * nu) * y * (H - y)
  for n = 1, 999, 2 do
    local decay = math.exp(-n * n * math.pi ^ 2 * nu * t / (H * H))
    if decay < 1e-18 then break end
    u = u - 4 * F * H * H / (nu * math.pi ^ 3 * n ^ 3) * math.sin(n * math.pi * y / H) * decay
  end
  return u
end

local fluid = mpm.material.newtonian{ density = rho, viscosity = mu, sound_speed = c }

local function channel(transfer, N)
  local h = H / N
  local sim <close> = mpm.simulation{ dim = 2, grid = { size = { 4 * h, H }, cell = h },
    shape = "quadratic_bspline", shape_boundary = mpm.param("boundary", "wls"), scheme = { transfer = transfer, stress_update = "USF" },
    gravity = { F, 0 }, boundary = { left = "periodic", right = "periodic", bottom = "fixed", top = "fixed" },
    dt = { cfl = cfl }, thermo = 0, diagnostics = false }
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 4 * h, H } }, { material = fluid, per_axis = 2 })
  local res = { emax = {}, erms = {} }
  for k, frac in ipairs(fractions) do
    local t = frac * Tdiff
    sim:run{ time = t - sim:time() }
    local v, nc = sim:field("velocity")
    local uc = series(0.5 * H, t)
    local s2, emax = 0, 0
    local np = sim:particle_count()
    for i = 1, np do
      local y = sim:particle(i).x[2]
      local e = v[nc * (i - 1) + 1] - series(y, t)
      s2 = s2 + e * e
      emax = math.max(emax, math.abs(e))
    end
    res.emax[k], res.erms[k] = emax / uc, math.sqrt(s2 / np) / uc
  end
  res.steps = sim:step()
  return res
end

local function slope(hs, es)
  local n, sx, sy, sxx, sxy = #hs, 0, 0, 0, 0
  for i = 1, n do
    local lx, ly = math.log(hs[i]), math.log(es[i])
    sx, sy, sxx, sxy = sx + lx, sy + ly, sxx + lx * lx, sxy + lx * ly
  end
  return (n * sxy - sx * sy) / (n * sxx - sx * sx)
end

for _, transfer in ipairs(transfers) do
  local hs, es, finest = {}, {}, nil
  for _, N in ipairs(resolutions) do
    local r = channel(transfer, N)
    local m2 = 0
    for k = 1, #fractions do m2 = m2 + r.erms[k] ^ 2 end
    hs[#hs + 1], es[#es + 1] = H / N, math.sqrt(m2 / #fractions)
    print(string.format("poiseuille %-8s N = %3d (%5d steps): e_max %.4f %% %.4f %% %.4f %%, e_rms %.4f %% %.4f %% %.4f %% at t/T = %.2f %.2f %.2f",
      transfer, N, r.steps, 100 * r.emax[1], 100 * r.emax[2], 100 * r.emax[3],
      100 * r.erms[1], 100 * r.erms[2], 100 * r.erms[3], fractions[1], fractions[2], fractions[3]))
    finest = r
  end
  local order = slope(hs, es)
  print(string.format("poiseuille %-8s convergence order %.2f over N = %s (E = %s)", transfer, order,
    table.concat(resolutions, ", "), table.concat((function()
      local t = {}
      for i, e in ipairs(es) do t[i] = string.format("%.3e", e) end
      return t
    end)(), ", ")))
  if transfer == "APIC" then
    for k, frac in ipairs(fractions) do
      T.check(finest.emax[k] <= 0.02, "APIC at N = %d, t/T = %.2f: profile error %.3f %% above 2 %%",
              resolutions[#resolutions], frac, 100 * finest.emax[k])
    end
    T.check(order >= 1.7, "APIC convergence order %.2f below 1.7", order)
  end
end
T.done("poiseuille")

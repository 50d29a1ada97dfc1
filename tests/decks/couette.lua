-- Plane Couette start-up flow (004 §3.1 companion; VALIDATION.md): a
-- Newtonian fluid at rest between two no-slip plates y = 0 and y = H,
-- periodic along x; from t = 0 the top plate moves at V along x (a `velocity`
-- face), the bottom one is fixed. The exact profile is
--   u(y, t) = V y / H + sum_{n >= 1} 2 V / (n pi) (-1)^n sin(n pi y / H) exp(-n^2 pi^2 nu t / H^2).
-- Same fluid and discretisation as tests/decks/poiseuille.lua (004's data in
-- SI: H = 5 mm, rho = 1000 kg/m^3, mu = 0.5 Pa s, nu = 5e-4 m^2/s,
-- T = H^2/nu = 0.05 s, c = 11.8 m/s), V = 0.0625 m/s (Mach 0.005), quadratic
-- B-splines with the WLS correction at the plates, 2 x 2 particles per cell,
-- a slab 4 cells wide, cfl = 0.5.
--
-- Error norm: at each time t, e_p = u_p - u(y_p, t),
--   e_max(t) = max_p |e_p| / V,   e_rms(t) = sqrt(mean_p e_p^2) / V,
-- and for the convergence order E(h) = sqrt(mean over the three times of
-- e_rms^2), the order the least-squares slope of log E against log h.
--
-- Asserts (issue 4 item 3, VALIDATION.md): APIC at the finest resolution
-- within 3 % (e_max) of the series at t/T = 0.05, 0.15, 0.5, and its order
-- >= 1.7 (as for Poiseuille). FLIP0.99 is reported.
-- Quick (N = 8, 16, 32, 64, ~6 s): APIC e_max at N = 64 is 0.025 %,
-- 0.007 %, 0.0000 %, order 2.56; FLIP0.99 e_max 0.23 %, 0.18 %, 0.09 %,
-- order 1.86 (its error at N = 8-16 is large, 10-29 %, at t/T = 0.05 next to
-- the plate's start-up jump). Full (`--set full=true`, adds N = 128, ~25 s):
-- APIC e_max 0.008 %, 0.003 %, 0.0001 %, order 2.35; FLIP0.99 order 1.59.
-- Parameters: full, cells (list), transfers (list), boundary, cfl.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local full = mpm.param("full", false)
local H, rho, mu, K = 5e-3, 1000.0, 0.5, 1.4e5
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

local V = 0.0625

local function series(y, t)
  local u = V * y / H
  for n = 1, 5000 do
    local decay = math.exp(-n * n * math.pi ^ 2 * nu * t / (H * H))
    if decay < 1e-18 then break end
    u = u + 2 * V / (n * math.pi) * (n % 2 == 0 and 1 or -1) * math.sin(n * math.pi * y / H) * decay
  end
  return u
end

local fluid = mpm.material.newtonian{ density = rho, viscosity = mu, sound_speed = c }

local function channel(transfer, N)
  local h = H / N
  local sim <close> = mpm.simulation{ dim = 2, grid = { size = { 4 * h, H }, cell = h },
    shape = "quadratic_bspline", shape_boundary = mpm.param("boundary", "wls"), scheme = { transfer = transfer, stress_update = "USF" },
    boundary = { left = "periodic", right = "periodic", bottom = "fixed", top = { "velocity", v = { V, 0 } } },
    dt = { cfl = cfl }, thermo = 0, diagnostics = false }
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 4 * h, H } }, { material = fluid, per_axis = 2 })
  local res = { emax = {}, erms = {} }
  for k, frac in ipairs(fractions) do
    local t = frac * Tdiff
    sim:run{ time = t - sim:time() }
    local v, nc = sim:field("velocity")
    local uc = V
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
    print(string.format("couette %-8s N = %3d (%5d steps): e_max %.4f %% %.4f %% %.4f %%, e_rms %.4f %% %.4f %% %.4f %% at t/T = %.2f %.2f %.2f",
      transfer, N, r.steps, 100 * r.emax[1], 100 * r.emax[2], 100 * r.emax[3],
      100 * r.erms[1], 100 * r.erms[2], 100 * r.erms[3], fractions[1], fractions[2], fractions[3]))
    finest = r
  end
  local order = slope(hs, es)
  print(string.format("couette %-8s convergence order %.2f over N = %s (E = %s)", transfer, order,
    table.concat(resolutions, ", "), table.concat((function()
      local t = {}
      for i, e in ipairs(es) do t[i] = string.format("%.3e", e) end
      return t
    end)(), ", ")))
  if transfer == "APIC" then
    for k, frac in ipairs(fractions) do
      T.check(finest.emax[k] <= 0.03, "APIC at N = %d, t/T = %.2f: profile error %.3f %% above 3 %%",
              resolutions[#resolutions], frac, 100 * finest.emax[k])
    end
    T.check(order >= 1.7, "APIC convergence order %.2f below 1.7", order)
  end
end
T.done("couette")

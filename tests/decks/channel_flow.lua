-- Plane channel start-up flows between two plates, periodic along x: the
-- shared machinery of tests/decks/poiseuille.lua and couette.lua (fluid,
-- discretisation, error norms, convergence order, assertions). See those
-- decks for the cases, the norms and the figures.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local M = {}

local full = mpm.param("full", false)
M.H, M.rho, M.mu, M.K = 5e-3, 1000.0, 0.5, 1.4e5
M.nu = M.mu / M.rho
M.Tdiff = M.H * M.H / M.nu
local H, rho, mu, K, nu, Tdiff = M.H, M.rho, M.mu, M.K, M.nu, M.Tdiff
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
local fluid = mpm.material.newtonian{ density = rho, viscosity = mu, sound_speed = c }

-- the least-squares slope of log e against log h: the convergence order
local function log_slope(hs, es)
  local lx, ly = {}, {}
  for i = 1, #hs do lx[i], ly[i] = math.log(hs[i]), math.log(es[i]) end
  return T.slope(lx, ly)
end

--- M.study{ name, series = u(y, t), scale = function(t) the error's reference speed,
---          gravity = {gx, gy}, top = face condition of the top plate, tolerance }
function M.study(case)
  local function channel(transfer, N)
    local h = H / N
    local sim <close> = mpm.simulation{ dim = 2, grid = { size = { 4 * h, H }, cell = h },
      shape = "quadratic_bspline", shape_boundary = mpm.param("boundary", "wls"),
      scheme = { transfer = transfer, stress_update = "USF" }, gravity = case.gravity or { 0, 0 },
      boundary = { left = "periodic", right = "periodic", bottom = "fixed", top = case.top },
      dt = { cfl = cfl }, thermo = 0, diagnostics = false }
    sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 4 * h, H } }, { material = fluid, per_axis = 2 })
    local res = { emax = {}, erms = {} }
    for k, frac in ipairs(fractions) do
      local t = frac * Tdiff
      sim:run{ time = t - sim:time() }
      local v, nc = sim:field("velocity")
      local uc = case.scale(t)
      local s2, emax = 0, 0
      local np = sim:particle_count()
      for i = 1, np do
        local y = sim:particle(i).x[2]
        local e = v[nc * (i - 1) + 1] - case.series(y, t)
        s2 = s2 + e * e
        emax = math.max(emax, math.abs(e))
      end
      res.emax[k], res.erms[k] = emax / uc, math.sqrt(s2 / np) / uc
    end
    res.steps = sim:step()
    return res
  end

  for _, transfer in ipairs(transfers) do
    local hs, es, finest = {}, {}, nil
    for _, N in ipairs(resolutions) do
      local r = channel(transfer, N)
      local m2 = 0
      for k = 1, #fractions do m2 = m2 + r.erms[k] ^ 2 end
      hs[#hs + 1], es[#es + 1] = H / N, math.sqrt(m2 / #fractions)
      print(string.format("%s %-8s N = %3d (%5d steps): e_max %.4f %% %.4f %% %.4f %%, e_rms %.4f %% %.4f %% %.4f %% at t/T = %.2f %.2f %.2f",
        case.name, transfer, N, r.steps, 100 * r.emax[1], 100 * r.emax[2], 100 * r.emax[3],
        100 * r.erms[1], 100 * r.erms[2], 100 * r.erms[3], fractions[1], fractions[2], fractions[3]))
      finest = r
    end
    for i, N in ipairs(resolutions) do
      T.expect{ id = string.format("%s.%s.E_N%d", case.name, transfer, N), what = string.format("%s N = %d: E(h)", transfer, N),
                value = es[i], detail = true }
    end
    local order = log_slope(hs, es)
    local shown = {}
    for i, e in ipairs(es) do shown[i] = string.format("%.3e", e) end
    print(string.format("%s %-8s convergence order %.2f over N = %s (E = %s)", case.name, transfer, order,
      table.concat(resolutions, ", "), table.concat(shown, ", ")))
    -- APIC is held to the tolerance and the order; the blend is reported
    local held = transfer == "APIC"
    for k, frac in ipairs(fractions) do
      T.expect{ id = string.format("%s.%s.emax_%g", case.name, transfer, frac),
                what = string.format("%s e_max at N = %d, t/T = %.2f", transfer, resolutions[#resolutions], frac),
                value = 100 * finest.emax[k], max = held and 100 * case.tolerance or nil, unit = "%" }
    end
    T.expect{ id = string.format("%s.%s.order", case.name, transfer), what = transfer .. " convergence order",
              value = order, min = held and 1.7 or nil }
  end
  T.done(case.name)
end

return M

-- moraine.analytic: closed-form references the verification decks and the
-- examples compare with, in one place.
--
--   local analytic = require "moraine.analytic"
--   local u = analytic.poiseuille(y, t, { H = 1e-3, nu = 1e-6, F = 1e-4 })
local M = {}

-- Terms of a Fourier series are summed until the exponential decay of the
-- next one falls below this (the series then agrees with its limit to round-off).
local DECAY_FLOOR = 1e-18

local function decay(n, nu, t, H) return math.exp(-n * n * math.pi ^ 2 * nu * t / (H * H)) end

-- Plane Poiseuille start-up between no-slip plates y = 0 and y = H, fluid at
-- rest at t = 0 driven by a body force F per unit mass, kinematic viscosity nu
-- (Morris, Fox & Zhu 1997; 004 §3.1; VALIDATION.md):
--   u = F/(2 nu) y (H - y) - sum_{n odd} 4 F H^2 / (nu pi^3 n^3) sin(n pi y / H) exp(-n^2 pi^2 nu t / H^2)
function M.poiseuille(y, t, p)
  local H, nu, F = p.H, p.nu, p.F
  local u = F / (2 * nu) * y * (H - y)
  for n = 1, 9999, 2 do
    local d = decay(n, nu, t, H)
    if d < DECAY_FLOOR then break end
    u = u - 4 * F * H * H / (nu * math.pi ^ 3 * n ^ 3) * math.sin(n * math.pi * y / H) * d
  end
  return u
end

-- Plane Couette start-up: the plate y = H set moving at V at t = 0, y = 0 at
-- rest (VALIDATION.md):
--   u = V y / H + sum_n 2 V / (n pi) (-1)^n sin(n pi y / H) exp(-n^2 pi^2 nu t / H^2)
function M.couette(y, t, p)
  local H, nu, V = p.H, p.nu, p.V
  local u = V * y / H
  for n = 1, 9999 do
    local d = decay(n, nu, t, H)
    if d < DECAY_FLOOR then break end
    u = u + 2 * V / (n * math.pi) * (n % 2 == 0 and 1 or -1) * math.sin(n * math.pi * y / H) * d
  end
  return u
end

return M

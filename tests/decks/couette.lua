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
local flow = dofile(mpm.deck_dir .. "/channel_flow.lua")
local H, nu, V = flow.H, flow.nu, 0.0625

local analytic = require "moraine.analytic"
local function series(y, t) return analytic.couette(y, t, { H = H, nu = nu, V = V }) end

flow.study{ name = "couette", series = series, scale = function() return V end,
            top = { "velocity", v = { V, 0 } }, tolerance = 0.03 }

-- A rigid strip footing pushed into a cohesive soil through a wall of
-- prescribed motion (sim:add_wall), against Prandtl's q_u = (2 + pi) c: the
-- set-up of examples/prandtl_footing (run from here with its parameters):
-- the soil of 002 §5.2 (von Mises with yield sqrt(3) c, a Tresca soil in
-- plane strain, c = 10 kPa, E = 1000 MPa, nu = 0.333, no gravity), half the
-- footing (B/2 = 0.5 m) against the slip face x = 0, a smooth footing moving
-- down at 4 mm/s after a half-cosine start, cells h = B/(2k + 1), quadratic
-- B-splines with WLS at the faces, TPIC + USF.
--
-- Asserted at each resolution: the footing pressure q = force_y / (B/2), its
-- mean over the last tenth of a settlement of 4e-4 B, within 5 % of q_u
-- (issue: the Prandtl case within 5 % through the wall); the wall's reaction
-- against sigma_yy integrated across the width at depth B (equilibrium of
-- the weightless soil: 2 %); the loading quasi-static, the kinetic energy
-- under 1 % of the plastic work. Quick: h = B/7 and B/11 (4900 and 12100
-- particles, 0.4 mm), q/q_u = 1.022 and 1.022, reaction/section 0.990 and
-- 0.988, E_k / W_pl at most 1.4e-3 over the second half. Full (`--set
-- full=true`): h = B/7, B/11, B/21 to 1 mm = 1e-3 B (q/q_u at 4e-4 B 1.022,
-- 1.022, 1.019); a rough footing at B/11 and B/21 (1.053, 1.040: its corner
-- converges more slowly; held to 10 %); Mohr-Coulomb phi = 0 at B/11
-- (1.024); doc/validation.md, "Prandtl footing through a wall". Beyond q_u the
-- pressure keeps rising, less on finer grids (q/q_u at 1e-3 B: 1.075,
-- 1.056, 1.037): volumetric locking of the isochoric plastic flow, which
-- the explicit step has no averaging against; held to 10 %.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local example = mpm.deck_dir .. "/../../examples/prandtl_footing/deck.lua"
local full = mpm.param("full", false)
local param = mpm.param

local function footing(set)
  mpm.param = function(name, default)
    if set[name] ~= nil then return set[name] end
    if name == "vtk" then return false end
    return param(name, default)
  end
  local ok, r = pcall(dofile, example)
  mpm.param = param
  if not ok then error(r, 0) end
  return r
end

local function check(name, r, what, rtol)
  local id = "prandtl_footing." .. name
  T.expect{ id = id .. ".q", what = string.format("%s, h = B/%d: q at settlement 4e-4 B", what, 2 * r.k + 1),
            value = r.q_04, reference = r.qu, rtol = rtol or 0.05, unit = "Pa" }
  if r.travel > 4e-4 then
    T.expect{ id = id .. ".q_1e-3", what = string.format("%s, h = B/%d: q at settlement 1e-3 B", what, 2 * r.k + 1),
              value = r.q_end, reference = r.qu, rtol = 0.10, unit = "Pa" }
  end
  T.expect{ id = id .. ".section", what = string.format("%s, h = B/%d: wall reaction against sigma_yy across the"
                                                         .. " width at depth B", what, 2 * r.k + 1),
            value = r.force, reference = r.section, rtol = 0.02, unit = "N/m" }
  T.expect{ id = id .. ".quasi_static", what = string.format("%s, h = B/%d: E_kinetic / W_plastic over the second"
                                                               .. " half", what, 2 * r.k + 1),
            value = r.ek_ratio, max = 0.01 }
end

local travel = full and 1e-3 or 4e-4
for _, k in ipairs(full and { 3, 5, 10 } or { 3, 5 }) do
  check("smooth_B" .. (2 * k + 1), footing{ k = k, travel = travel, tag = "smooth_k" .. k }, "smooth, von Mises")
end
if full then
  for _, k in ipairs{ 5, 10 } do
    check("rough_B" .. (2 * k + 1), footing{ k = k, travel = 4e-4, rough = true, tag = "rough_k" .. k },
          "rough, von Mises", 0.10)
  end
  check("mohr_coulomb_B11", footing{ k = 5, travel = 4e-4, material = "mohr_coulomb", tag = "mc_k5" },
        "smooth, Mohr-Coulomb phi = 0")
end
T.done("prandtl_footing")

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
-- 1.056, 1.037): volumetric locking of the isochoric plastic flow; held to
-- 10 %, the rise per 1e-3 B reported (8.8, 5.7, 3.0 % of q_u).
-- With scheme volumetric = "fbar" (the divergence averaged over the nodes)
-- the load levels off: at h = B/7, B/11, B/21 q/q_u at 1e-3 B is 0.956,
-- 0.971, 0.985 (held to 5 %) and rises by 0.97, 0.43, 0.13 % of q_u per
-- 1e-3 B after 4e-4 B (held to 2 %); at B/11, nu = 0, 0.333, 0.45 give
-- 0.966, 0.971, 0.980 (the spread held to 2 % of q_u). Quick: B/11 only.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local full = mpm.param("full", false)

local function footing(set)
  if set.vtk == nil then set.vtk = false end
  return T.run_example("../../examples/prandtl_footing/deck.lua", set)
end

-- the reaction against the section and the quasi-static loading
local function balance(id, r, where)
  T.expect{ id = id .. ".section", what = where .. ": wall reaction against sigma_yy across the width at depth B",
            value = r.force, reference = r.section, rtol = 0.02, unit = "N/m" }
  T.expect{ id = id .. ".quasi_static", what = where .. ": E_kinetic / W_plastic over the second half",
            value = r.ek_ratio, max = 0.01 }
end

-- the rise of q / q_u per 1e-3 B of settlement from 4e-4 B to the end
local function rise(r) return (r.q_end - r.q_04) / r.qu / ((r.travel - 4e-4) / 1e-3) end

local function check(name, r, what, rtol)
  local id = "prandtl_footing." .. name
  local where = string.format("%s, h = B/%d", what, 2 * r.k + 1)
  T.expect{ id = id .. ".q", what = where .. ": q at settlement 4e-4 B", value = r.q_04, reference = r.qu,
            rtol = rtol or 0.05, unit = "Pa" }
  if r.travel > 4e-4 then
    T.expect{ id = id .. ".q_1e-3", what = where .. ": q at settlement 1e-3 B", value = r.q_end, reference = r.qu,
              rtol = 0.10, unit = "Pa" }
    T.expect{ id = id .. ".rise", what = where .. ": rise of q / q_u per 1e-3 B after 4e-4 B (locking)",
              value = rise(r), asserted = false }
  end
  balance(id, r, where)
end

-- scheme volumetric = "fbar": the load levels off at the limit
local function plateau(name, r, what)
  local id = "prandtl_footing." .. name
  local where = string.format("%s, h = B/%d, volumetric = fbar", what, 2 * r.k + 1)
  T.expect{ id = id .. ".q_1e-3", what = where .. ": q at settlement 1e-3 B", value = r.q_end, reference = r.qu,
            rtol = 0.05, unit = "Pa" }
  T.expect{ id = id .. ".rise", what = where .. ": rise of q / q_u per 1e-3 B after 4e-4 B", value = rise(r),
            max = 0.02 }
  balance(id, r, where)
end

local travel = full and 1e-3 or 4e-4
for _, k in ipairs(full and { 3, 5, 10 } or { 3, 5 }) do
  check("smooth_B" .. (2 * k + 1), footing{ k = k, travel = travel, tag = "smooth_k" .. k }, "smooth, von Mises")
end
local fbar = {}
for _, k in ipairs(full and { 3, 5, 10 } or { 5 }) do
  fbar[k] = footing{ k = k, travel = 1e-3, volumetric = "fbar", tag = "fbar_k" .. k }
  plateau("fbar_B" .. (2 * k + 1), fbar[k], "smooth, von Mises")
end
if full then
  -- a limit load does not depend on the elastic constants: with the
  -- averaging, Poisson's ratio moves q at 1e-3 B by little (without it, by
  -- 8 % of q_u from nu = 0 to 0.45)
  local q = { fbar[5].q_end }
  for _, nu in ipairs{ 0, 0.45 } do
    local r = footing{ k = 5, travel = 1e-3, volumetric = "fbar", nu = nu, tag = "fbar_k5_nu" .. nu }
    T.expect{ id = "prandtl_footing.fbar_B11_nu" .. nu .. ".q_1e-3", what = string.format("smooth, von Mises, h = B/11,"
              .. " volumetric = fbar, nu = %g: q at settlement 1e-3 B", nu), value = r.q_end, reference = r.qu,
              rtol = 0.05, unit = "Pa" }
    q[#q + 1] = r.q_end
  end
  T.expect{ id = "prandtl_footing.fbar_B11.nu_spread", what = "smooth, von Mises, h = B/11, volumetric = fbar:"
            .. " q at 1e-3 B, largest minus smallest over nu = 0, 0.333, 0.45, over q_u",
            value = (math.max(table.unpack(q)) - math.min(table.unpack(q))) / fbar[5].qu, max = 0.02 }
  for _, k in ipairs{ 5, 10 } do
    check("rough_B" .. (2 * k + 1), footing{ k = k, travel = 4e-4, rough = true, tag = "rough_k" .. k },
          "rough, von Mises", 0.10)
  end
  check("mohr_coulomb_B11", footing{ k = 5, travel = 4e-4, material = "mohr_coulomb", tag = "mc_k5" },
        "smooth, Mohr-Coulomb phi = 0")
end
T.done("prandtl_footing")

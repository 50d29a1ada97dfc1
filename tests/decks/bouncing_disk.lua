-- Bouncing elastic disk of Love & Sulsky (CMAME 2006, §4.1), as 000 repeats
-- it in App. B.1 (Fig. 24): a 2D disk without gravity, set moving by an
-- initial velocity, bounces off the walls of a box; PIC, FLIP and APIC.
-- 000's settings: Hooke's law, USL, boundary-modified cubic B-splines.
-- Assumed (the source's geometry, material and discretisation were not at
-- hand; units are SI but the case is scale-free): a disk of radius 1 m in a
-- 5 m x 5 m box with slip walls, starting at its centre with v = (0.1, 0.05)
-- m/s; rho = 1 kg/m^3, E = 10 Pa, nu = 0.3; l_cell = 0.25 m, 2 x 2 points per
-- cell, a_tau = 0.2; 100 s (000 Fig. 24 discusses t up to past 50 s).
-- Each run's energies go to disk_<transfer>.csv.
-- --set transfers=..., a_tau=..., time=T pick a part.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local duration = mpm.param("time", 100.0)
local a_tau = mpm.param("a_tau", 0.2)
local mat = mpm.material.linear_elastic{ density = 1, E = 10, nu = 0.3 }

local function bounce(transfer)
  local sim = mpm.simulation{
    dim = 2, grid = { size = { 5, 5 }, cell = 0.25 }, shape = "cubic_bspline", shape_boundary = "modified",
    scheme = { transfer = transfer, stress_update = "USL" }, dt = { a_tau = a_tau }, boundary = { all = "slip" },
    thermo = 0, diagnostics = string.format("disk_%s.csv", transfer), diagnostics_every = 20,
  }
  sim:add_particles(mpm.disk{ center = { 2.5, 2.5 }, radius = 1 }, { material = mat, per_axis = 2,
                    velocity = { 0.1, 0.05 } })
  local e0 = sim:energy().total
  -- every strategy takes the same steps (dt depends on the material and cell
  -- only), so the k-th samples of two runs are at the same time
  local r = { e0 = e0, rise = 0, history = {} }
  local steps = 0
  sim:hook{ every_steps = 1, fn = function(s)
    local e = s:energy().total
    r.rise = math.max(r.rise, (e - e0) / e0)
    steps = steps + 1
    if steps % 20 == 0 then r.history[#r.history + 1] = e / e0 end
  end }
  sim:run{ time = duration }
  r.kept = sim:energy().total / e0
  sim:free()
  return r
end

--- largest |E_a - E_b| / E0 over the run
local function apart(a, b)
  local d = 0
  for k = 1, math.min(#a.history, #b.history) do d = math.max(d, math.abs(a.history[k] - b.history[k])) end
  return d
end

local r, id = {}, "bouncing_disk."
local transfers = T.list(mpm.param("transfers", "PIC,FLIP,APIC"))
for _, transfer in ipairs(transfers) do
  r[transfer] = bounce(transfer)
  print(string.format("bouncing disk %-4s a_tau %g: E0 = %.5g J/m, E/E0 = %.4f after %g s, largest rise %.3g",
                      transfer, a_tau, r[transfer].e0, r[transfer].kept, duration, r[transfer].rise))
  T.expect{ id = id .. transfer .. ".kept", value = r[transfer].kept, asserted = false,
            what = string.format("%s: E_tot / E0 after %g s (000 Fig. 24)", transfer, duration) }
  -- USL is dissipative by formulation (000 App. A): E_tot never rises above E0
  -- by more than the round-off of summing the particles' energies
  T.expect{ id = id .. transfer .. ".rise", value = r[transfer].rise, max = 1e-6,
            what = string.format("%s: largest rise of E_tot above E0, relative (000 App. A: USL dissipates)", transfer) }
end
if r.PIC and r.APIC then
  T.expect{ id = id .. "PIC_vs_APIC", value = 100 * apart(r.PIC, r.APIC), min = 5, unit = "%",
            what = "largest |E_PIC - E_APIC| / E0 over the run (000: \"noticeably different\" in this 2D case)" }
end
if r.FLIP and r.PIC and r.APIC then
  T.expect{ id = id .. "FLIP_keeps", value = r.FLIP.kept, min = math.max(r.PIC.kept, r.APIC.kept),
            what = string.format("FLIP: E_tot / E0 at the end, above PIC's (%.3g) and APIC's (%.3g) (000 §4.1, App. A)",
                                 r.PIC.kept, r.APIC.kept) }
end
T.done("bouncing_disk")

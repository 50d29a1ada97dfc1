-- Bouncing cube (000 §4.1): 5 x 5 x 13 cells of 0.2 m, a 1 m cube between
-- z = 1 and 2 m with 8 points per cell at the Gauss points, E = 12.84 MPa,
-- nu = 0.16, rho = 1748 kg/m^3, g = 9.81, slip walls, a_tau = 0.05.
-- FLIP + USF keeps the total energy within 3 % of its initial value through
-- the first two bounces; PIC + USF loses nearly all of it at the first impact
-- and does not bounce back above half its drop height.
-- --set transfer=... --set time=... run one case (the validation target).
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local mat = mpm.material.linear_elastic{ density = 1748, E = 12.84e6, nu = 0.16 }

local function cube(transfer, duration, csv)
  local sim = mpm.simulation{
    dim = 3, grid = { size = { 1, 1, 2.6 }, cell = 0.2 }, gravity = { 0, 0, -9.81 },
    scheme = { transfer = transfer, stress_update = "USF" }, dt = { a_tau = 0.05 },
    boundary = { all = "slip", top = "free" }, thermo = 2000, diagnostics = csv,
  }
  sim:add_particles(mpm.box{ min = { 0, 0, 1 }, max = { 1, 1, 2 } }, { material = mat, per_axis = 2 })
  local e0 = sim:energy().total
  local worst, lowest_after, top_after, impact = 0, math.huge, -math.huge, false
  sim:hook{ every_steps = 10, fn = function(s)
    local e = s:energy().total
    worst = math.max(worst, math.abs(e - e0) / e0)
    local z = s:diagnostics().center_of_mass[3]
    local vz = s:diagnostics().com_velocity[3]
    -- the impact stops the fall: the first time the cube no longer moves down
    if s:time() > 0.1 and vz >= 0 then impact = true end
    if impact then top_after = math.max(top_after, z) end
  end }
  sim:run{ time = duration }
  return sim, e0, worst, impact, top_after
end

local only = mpm.param("transfer", "")
if only == "" or only == "FLIP" then
  local sim, e0, worst = cube("FLIP", mpm.param("time", 1.9), "cube_flip.csv")
  print(string.format("bouncing cube FLIP: E_ref = %.4g J, largest total-energy drift %.2f %% over %.2f s", e0,
                      100 * worst, sim:time()))
  T.expect{ id = "bouncing_cube.flip.E_ref", what = "initial total energy (000: about 25.7 kJ)", value = e0,
             reference = 25.7e3, rtol = 0.01, unit = "J" }
  T.expect{ id = "bouncing_cube.flip.drift", what = string.format("FLIP largest total-energy drift over %.2f s", sim:time()),
             value = 100 * worst, max = 3, unit = "%" }
end
if only == "" or only == "PIC" then
  local sim, e0, worst, impact, top = cube("PIC", mpm.param("time", 1.2), "cube_pic.csv")
  print(string.format("bouncing cube PIC: centre of mass rose back to %.3f m after the impact (dropped from 1.5 m)", top))
    T.check(impact, "the PIC cube never reached the floor")
  -- half the drop height: the centre of mass starts at 1.5 m and lands at 0.5 m
  T.expect{ id = "bouncing_cube.pic.top", what = "PIC: highest centre of mass after the impact (half the drop: 1.0 m)",
             value = top, max = 1.0, unit = "m" }
end
T.done("bouncing_cube")

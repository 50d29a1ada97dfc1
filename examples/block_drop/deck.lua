-- A 2D elastic block (plane strain) is thrown onto a rough floor: it falls,
-- lands, bounces and slides, and Coulomb friction (mu = 0.3) on the floor
-- takes energy out, accounted as W_friction in the diagnostics (000, Eq. 66).
--
--   moraine examples/block_drop/deck.lua -o out/block
local quick = mpm.param("quick", false)
local block = mpm.material.linear_elastic{ density = 1000, E = 2e6, nu = 0.3 }

local sim = mpm.simulation{
  dim = 2,
  grid = { size = { 4, 2 }, cell = 0.05 },
  gravity = { 0, -9.81 },
  scheme = { transfer = mpm.param("transfer", "FLIP0.99"), stress_update = "USF" },
  boundary = { left = "slip", right = "slip", top = "free", bottom = { "friction", mu = mpm.param("mu", 0.3) } },
  dt = { a_tau = 0.2 },
  thermo = 1000,
  output = { vtk = "block", every = 0.02 },
}
sim:add_particles(mpm.box{ min = { 0.3, 0.8 }, max = { 0.9, 1.2 } }, { material = block, per_axis = 2,
                  velocity = { 3.0, 0 } })

-- record the position of the block's front every 0.1 s from a hook
local front = {}
sim:hook{ every_time = 0.1, fn = function(s)
  front[#front + 1] = string.format("%.2f s: centre of mass at x = %.3f m", s:time(), s:diagnostics().com_x)
end }
sim:run{ time = quick and 0.1 or mpm.param("time", 1.5) }
for i = 1, #front, 5 do print(front[i]) end
local e = sim:energy()
print(string.format("block drop: E_total = %.4g J/m, friction work W_friction = %.4g J/m", e.total, e.friction))

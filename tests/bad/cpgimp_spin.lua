-- expect: cpgimp_spin.lua:10: run\{\}: step [0-9]+: particle [0-9]+ at \([^)]*\): shape = 'cpgimp' sizes its box along [xy] by F_([xy])\1 = [^:]*: the box has collapsed or turned over \(a shear or rotation an axis-aligned box does not follow; shape = 'cpdi' follows them\)
-- case: runtime | cpGIMP on a body turning a quarter turn: F_xx reaches 0
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.05 }, shape = "cpgimp", gravity = {0, 0},
                            thermo = 0, diagnostics = false }
local w = 2 * math.pi -- rad/s: a quarter turn in 0.25 s
sim:add_particles(mpm.box{ min = {0.4, 0.4}, max = {0.6, 0.6} },
                  { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 },
                    velocity = function(x, y) return -w * (y - 0.5), w * (x - 0.5) end })
sim:run{ time = 0.5 }

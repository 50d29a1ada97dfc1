-- expect: implicit_switch_option.lua:4: simulation\{\} implicit: bbar must be a boolean, got number
-- case: types | a wrong option of integrator = "implicit" is reported where the simulation is made
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, shape = "gimp",
                            integrator = "implicit", implicit = { bbar = 1 } }

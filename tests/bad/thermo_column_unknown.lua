-- expect: thermo_column_unknown.lua:4: simulation\{\} thermo: columns\[3\] = 'E_kin' is not valid \(did you mean 'E_kinetic'\?\); valid: 'step', 'time', 'dt', 'steps_per_s', 'E_kinetic', .*'W_MPM', .*'particles'$
-- case: choices | an unknown thermo column (`E_kin`)
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 },
  thermo = { every = 10, columns = { "step", "time", "E_kin" } } }

-- expect: cpdi2_3d\.lua:4: simulation\{\}: shape = 'cpdi2' is 2D only \(its domains are quadrilaterals\); use shape = 'cpdi' in 3D
-- case: choices | CPDI2 in 3D
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 3, grid = { size = {1, 1, 1}, cell = 0.1 }, shape = "cpdi2" }

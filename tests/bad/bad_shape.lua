-- expect: bad_shape.lua:4: simulation\{\}: shape = 'quadratic' is not valid \(did you mean 'quadratic_bspline'\?\); valid: 'linear', 'gimp', 'quadratic_bspline', 'cubic_bspline', 'cpdi', 'cpdi2', 'cpgimp'
-- case: choices | a shape-function name that does not exist
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, shape = "quadratic" }

-- expect: polygon_two_vertices\.lua:4: polygon\{\}: vertices must list at least 3 points, got 2
-- case: geometry | a polygon with two vertices
local mpm = require "moraine"
local p = mpm.polygon{ vertices = { {0, 0}, {1, 1} } }

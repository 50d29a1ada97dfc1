-- expect: source_overlap\.lua:8: add_source\{\}: source 'b': region: the inlet box overlaps that of source 'a' \(sources may not overlap\)
-- case: geometry | two inflow sources whose inlet boxes overlap
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 0.4}, cell = 0.05 }, thermo = 0, diagnostics = false, series = false }
sim:add_source{ name = "a", region = mpm.box{ min = {0, 0}, max = {0.1, 0.2} }, material = mat, velocity = {0.1, 0} }
-- the second inlet reaches down into the first one's box
sim:add_source{ name = "b", region = mpm.box{ min = {0, 0.15}, max = {0.1, 0.4} }, material = mat, velocity = {0.1, 0} }

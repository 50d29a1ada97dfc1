-- expect: unknown_transfer.lua:4: simulation\{\} scheme: transfer: unknown strategy 'FLIPP'.*valid: PIC, FLIP
-- case: choices | a misspelt transfer strategy
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, scheme = { transfer = "FLIPP" } }

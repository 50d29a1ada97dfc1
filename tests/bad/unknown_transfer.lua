-- expect: unknown_transfer.lua:3: simulation\{\} scheme: transfer: unknown strategy 'FLIPP'.*valid: PIC, FLIP
local mpm = require "moraine"
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, scheme = { transfer = "FLIPP" } }

-- expect: parallel_io_mode.lua:4: parallel_io\(\): mode = 'twice' is not valid; valid: 'once', 'every'
-- case: choices | a mode of the deck's own file writes that does not exist
local mpm = require "moraine"
mpm.parallel_io("twice")

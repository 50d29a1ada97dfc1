-- expect: safe_open_outside\.lua:5: io\.open\(\): '/tmp/moraine-safe-outside\.txt' is outside the output directory '.*'; --safe allows writes only below the output directory
-- case: permission | --safe: a deck opens a file outside the output directory for writing
-- options: --safe
-- status: 1
local f = io.open("/tmp/moraine-safe-outside.txt", "w")
error("io.open outside the output directory was not refused")

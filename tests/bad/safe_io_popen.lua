-- expect: safe_io_popen\.lua:5: io\.popen\(\): not available with --safe \(it runs a program\)
-- case: permission | --safe: a deck runs a program with io.popen
-- options: --safe
-- status: 1
local pipe = io.popen("id", "r")
error("io.popen was not refused")

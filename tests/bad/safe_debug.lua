-- expect: safe_debug\.lua:5: debug\.getregistry\(\): not available with --safe \(the debug library reaches past the other restrictions\)
-- case: permission | --safe: a deck uses the debug library (only debug.traceback is kept)
-- options: --safe
-- status: 1
local registry = debug.getregistry()
error("debug.getregistry was not refused")

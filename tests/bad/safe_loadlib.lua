-- expect: safe_loadlib\.lua:5: package\.loadlib\(\): not available with --safe \(it loads native code\)
-- case: permission | --safe: a deck loads a shared library with package.loadlib
-- options: --safe
-- status: 1
local f = package.loadlib("libc.so.6", "system")
error("package.loadlib was not refused")

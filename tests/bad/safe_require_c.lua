-- expect: safe_require_c\.lua:10: require\('evil'\): '.*/evil\.so' is a C module: not loaded with --safe \(it runs native code\)
-- case: permission | --safe: a deck requires a C module (a shared library on package.cpath)
-- options: --safe
-- status: 1
-- the searcher refuses the module it finds before anything loads it, so a
-- stand-in file is enough
local f = assert(io.open(mpm.outdir .. "/evil.so", "w"))
f:close()
package.cpath = mpm.outdir .. "/?.so"
require("evil")
error("require of a C module was not refused")

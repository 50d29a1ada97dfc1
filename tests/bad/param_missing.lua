-- expect: param_missing\.lua:4: param\('cells'\): not given with --set and no default
-- case: keys | mpm.param without --set and without a default
local mpm = require "moraine"
local n = mpm.param("cells")

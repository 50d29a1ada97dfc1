-- expect: warnings_unknown\.lua:4: warnings\{\}: ignore = 'dt_above_cf' is not valid \(did you mean 'dt_above_cfl'\?\); valid: 'dt_above_cfl', 'courant_above_one', 'one_particle_per_cell', 'checkpoint_no_checksums', 'unused_set', 'all'
-- case: keys | a misspelt warning ID in mpm.warnings
local mpm = require "moraine"
mpm.warnings{ ignore = { "dt_above_cf" } }

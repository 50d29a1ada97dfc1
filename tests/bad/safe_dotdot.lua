-- expect: safe_dotdot\.lua:5: io\.open\(\): '.*/\.\./escape\.txt' is outside the output directory '.*'; --safe allows writes only below the output directory
-- case: permission | --safe: a deck climbs out of the output directory with '..'
-- options: --safe
-- status: 1
local f = io.open(mpm.outdir .. "/sub/../../escape.txt", "a")
error("a '..' escape was not refused")

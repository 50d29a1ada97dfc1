-- expect: load_missing.lua:3: load\(\): 'no_such_checkpoint.h5': cannot open: No such file or directory
-- case: files | a checkpoint that does not exist
local sim = mpm.load("no_such_checkpoint.h5")

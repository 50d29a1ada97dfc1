-- expect: load_missing.lua:2: load\(\): 'no_such_checkpoint.h5': cannot open: No such file or directory
local sim = mpm.load("no_such_checkpoint.h5")

-- expect: load_directory\.lua:4: load\(\): '.*': is a directory, not a checkpoint file
-- case: files | a directory given as the checkpoint
local mpm = require "moraine"
local sim = mpm.load(mpm.outdir)

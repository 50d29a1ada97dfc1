-- mpm.resume in a deck (tests/robust/resume.sh): the checkpoint of
-- resume_run.lua's second run{}, its hook set again, the run finished.
local sim = mpm.resume(mpm.param("from", "block_interrupted.h5"))
sim:hook{ every_steps = 10, fn = function(s) s:record("kinetic_x2", 2 * s:energy().kinetic) end }
sim:run{}

-- expect: resume_not_resumable\.lua:9: resume\(\): '.*inside\.h5' holds no run to continue \(a checkpoint of sim:save\(\) made inside a run, or of an older moraine\): load it with mpm\.load
-- case: files | mpm.resume of a checkpoint written inside a run by sim:save()
local mpm = require "moraine"
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, dt = { fixed = 1e-4 } }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat })
sim:hook{ every_steps = 1, fn = function(s) s:save("inside.h5") end }
sim:run{ steps = 1 }
mpm.resume("inside.h5")

-- expect: safe_output_outside\.lua:5: simulation\{\}: vtk: '/tmp/moraine-safe-run/disks\.pvd' is outside the output directory '.*'; --safe allows writes only below the output directory
-- case: permission | --safe: a VTK series named into a directory outside the output directory
-- options: --safe
-- status: 1
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, output = { vtk = "/tmp/moraine-safe-run/disks" } }
error("an output outside the output directory was not refused")

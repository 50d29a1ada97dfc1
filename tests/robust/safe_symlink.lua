-- moraine --safe: writes through a symbolic link in the output directory
-- that leads outside it (tests/robust/safe_symlink.sh makes the links).
--   --set through=dir   io.open of a file under the link to a directory
--   --set through=file  the diagnostics CSV named as a link to a file
local through = mpm.param("through", "dir")
if through == "dir" then
  local f = io.open(mpm.outdir .. "/link/stolen.txt", "w")
else
  mpm.simulation{ dim = 2, grid = { size = { 1, 1 }, cell = 0.1 }, diagnostics = "linked.csv" }
end
error("the write through the link was not refused")

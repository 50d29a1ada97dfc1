-- The colliding cylinders of 001 §7.2-7.3, shared by the implicit decks
-- (implicit_cylinders, implicit_run, implicit_cutbacks, implicit_restart):
-- two disks of radius 2 m centred at (5.8, 5.5) and (14.2, 6.5), moving
-- towards each other at 0.75 m/s, on a 20 m x 12 m grid of 2 m cells with
-- linear shape functions, points on a regular pattern. Returns
-- function(material, options) -> simulation; options: per_cell (default
-- 16), diagnostics (default false), output (default none).
return function(mat, o)
  o = o or {}
  local sim = mpm.simulation{ dim = 2, grid = { size = { 20, 12 }, cell = 2 }, shape = "linear", thermo = 0,
                              diagnostics = o.diagnostics or false, series = false, output = o.output }
  for _, c in ipairs{ { 5.8, 5.5, 0.75 }, { 14.2, 6.5, -0.75 } } do
    sim:add_particles(mpm.disk{ center = { c[1], c[2] }, radius = 2 },
                      { material = mat, velocity = { c[3], 0 }, per_cell = o.per_cell or 16, placement = "regular" })
  end
  return sim
end

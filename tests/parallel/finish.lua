-- The end the equivalence decks share (equivalence.lua, particles.lua,
-- walls.lua): the final state saved for tests/parallel/equivalence.py, and
-- a line of the run and one of the slabs printed.
--   local par = dofile(mpm.deck_dir .. "/finish.lua")(sim, name)
return function(sim, name)
  sim:save(name .. ".h5")
  local d = sim:diagnostics()
  print(string.format("%s: %d steps, %d particles, E_total %.12g, W_MPM %.6g", name, sim:step(), d.particles,
                      d.E_total, d.W_MPM))
  local par = sim:parallel()
  if par.cuts then
    print(string.format("%d processes, slabs cut at cell rows %s along the last axis; %d re-cuts, %d particles " ..
                        "sent, %.3g MB of halo sums", par.size, table.concat(par.cuts, " "), par.rebalances,
                        par.migrated, par.halo_bytes / 1e6))
  end
  return par
end

-- moraine robustness: the warnings for legal but suspicious choices, for
-- tests/robust/warnings.sh. --set silence=ID silences one from the deck.
local mpm = require "moraine"
local silence = mpm.param("silence", "")
if silence ~= "" then mpm.warnings{ ignore = { silence } } end
local mat = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }
local sim = mpm.simulation{ dim = 2, grid = { size = {1, 1}, cell = 0.1 }, thermo = 0, diagnostics = false,
  series = false }
sim:add_particles(mpm.box{ min = {0.2, 0.2}, max = {0.4, 0.4} }, { material = mat, per_axis = 1 })
local cfl = sim:dt_estimate().cfl
sim:set_dt{ fixed = 1.5 * cfl }   -- above the CFL estimate, still stable for a few steps
sim:run{ steps = 2 }
sim:set_dt{ cfl = 1.2 }           -- a Courant number above 1
sim:run{ steps = 2 }
sim:set_dt{ fixed = 2 * cfl }     -- the same warning again: printed once only
sim:run{ steps = 1 }

-- moraine.collapse: the granular column settling-and-collapse workflow of
-- 000 §5, written in Lua on top of the public API.
--
--   local collapse = require "moraine.collapse"
--   local r = collapse.run{ aspect_ratio = 1, strategy = "FLIP" }
--   print(r.runout, r.t_rest, r.W_MPM_ratio)
--
-- Two phases (000 §5.1):
--  1. settling: an elastic column of width `width` and height
--     `aspect_ratio * width` settles under gravity in a box exactly as wide as
--     the column (000, Eqs. 57-58), with Cundall damping (000, Eqs. 61-62),
--     until its kinetic energy has died out; the state is saved to an HDF5
--     checkpoint;
--  2. collapse: the settled particles are imported onto a grid six times
--     wider (000, Eq. 59) as Mohr-Coulomb material (000 Table 2), the right
--     wall is now 5 widths away, and the column collapses onto a floor with
--     Coulomb friction mu.
-- Measures (000 §5.1.4): the column width L_x from the furthest particle
-- (Eq. 70), the runout d_r = L_x - L_x^init (Eq. 71), the normalised runout
-- L~ = d_r / L_x^init (Eq. 72) and time t~ = t / sqrt(AR L_x^init / g)
-- (Eq. 73), the energies and the MPM energy error W_MPM (Eqs. 64-68)
-- normalised by |Delta E_p^stable| = |Delta E_g + Delta E_el| (Eq. 69).
-- The deviatoric strain eps_D (Eq. 75) is a particle field of the engine.
local mpm = rawget(_G, "mpm") or require "moraine"
local results = require "moraine.results"

local M = {}

--- 000 Table 2: Mohr-Coulomb parameters of the collapse (Camargue sand, the
-- preset camargue_sand of moraine.presets: density 1748 kg/m^3, E 1.284e7 Pa,
-- nu 0.16, phi 33.75 deg, psi 0, cohesion 1 Pa, tension -1 = the apex c / tan(phi)).
-- The settling uses a linear elastic material with the same density, E, nu.
M.table2 = require("moraine.presets").parameters("camargue_sand")
M.table2.model, M.table2.source = nil, nil

-- every option of collapse.run (and collapse.settle) with its default; false = none
local DEFAULTS = {
  aspect_ratio = false,        -- required: initial height / initial width
  width = 1.0,                 -- m, L_x^init of the column (000: 1 m)
  cell = 0.1,                  -- m, l_cell
  per_axis = 2,                -- particles per cell along each axis (N_mppc = per_axis^2)
  shape = "cubic_bspline",     -- 000 §2.3: boundary-modified cubic B-splines
  shape_boundary = "modified",
  strategy = "FLIP",           -- motion integration of the collapse (000 Table 1)
  settle_strategy = false,     -- of the settling; default: strategy
  stress_update = "USF",
  holds = "grid",              -- where FLIP's increment takes the holds of V (scheme holds), both phases
  volumetric = "standard",     -- the volumetric part of the velocity gradient (scheme volumetric), both phases
  a_tau = 0.2,                 -- dt = a_tau l_cell sqrt(rho / E) (000, Eq. 29)
  dt = false,                  -- a fixed dt (s) instead of a_tau
  dt_policy = false,           -- any dt policy table/function of the API instead
  density = M.table2.density,
  E = M.table2.E,
  nu = M.table2.nu,
  phi = M.table2.phi,
  psi = M.table2.psi,
  cohesion = M.table2.cohesion,
  tension = M.table2.tension,
  initial_stress = -1.0,       -- Pa, isotropic (000 §5.1.3: 1 Pa, not zero)
  g = 9.81,                    -- m/s^2
  friction = 0.3,              -- mu of the floor (000 §5.1.2)
  damping = 0.1,               -- Cundall D of the settling (000 §5.2, App. C)
  collapse_damping = 0.0,      -- Cundall D of the collapse
  settle_time = false,         -- s, the longest settling; default 40 column periods
  settle_until_ek = 1e-6,      -- stop settling once E_k stays below this fraction of its peak
  settled = false,             -- path of a settled checkpoint: skip the settling
  width_factor = 6,            -- W_mesh^collapse / W_mesh^settling (000, Eq. 59)
  headroom = 0,                -- empty cells above the column (000: none, Eq. 58)
  collapse_time = false,       -- s; default 8 sqrt(AR width / g)
  stop_at_rest = false,        -- end the collapse once at rest for rest_hold seconds
  rest_fraction = 0.05,        -- "at rest": E_k below this fraction of its peak
  rest_hold = 0.25,            -- s
  bulk_fraction = 0.95,        -- the mass fraction behind the bulk front (runout_mass)
  sample_every = 0.01,         -- s, the series sampling interval
  name = false,                -- prefix of the files; default AR<ar>_<strategy>
  csv = true,                  -- write <name>_series.csv
  diagnostics = true,          -- engine diagnostics CSVs <name>_settle.csv, <name>_collapse.csv
  diagnostics_every = 100,     -- steps
  vtk = false,                 -- true or {every = s, fields = {...}}: <name>_settle.pvd, <name>_collapse.pvd
  thermo = 0,
  keep = false,                -- keep (return) the simulation objects instead of freeing them
  material = false,            -- a material object for the collapse instead of the Mohr-Coulomb sand
  split = false,               -- particle splitting of the collapse, {stretch, max_level} (simulation{split})
}

local function check_options(opts)
  if type(opts) ~= "table" then error("collapse.run: expected a table of options", 3) end
  local o = {}
  for k, v in pairs(opts) do
    if type(k) ~= "string" then error("collapse.run: options must be named (key = value)", 3) end
    if DEFAULTS[k] == nil then
      local names = {}
      for n in pairs(DEFAULTS) do names[#names + 1] = n end
      table.sort(names)
      error(string.format("collapse.run: unknown option '%s' (valid: %s)", k, table.concat(names, ", ")), 3)
    end
    o[k] = v
  end
  for k, v in pairs(DEFAULTS) do
    if o[k] == nil and v ~= false then o[k] = v end
  end
  local ar = o.aspect_ratio
  if type(ar) ~= "number" or not (ar > 0) then
    error("collapse.run: aspect_ratio (initial height / width) must be a number > 0", 3)
  end
  if type(o.bulk_fraction) ~= "number" or not (o.bulk_fraction > 0 and o.bulk_fraction <= 1) then
    error("collapse.run: bulk_fraction must be a number in (0, 1]", 3)
  end
  for _, k in ipairs{ "width", "cell", "a_tau", "g", "sample_every", "width_factor" } do
    if type(o[k]) ~= "number" or not (o[k] > 0) then error("collapse.run: " .. k .. " must be a number > 0", 3) end
  end
  for _, k in ipairs{ "friction", "damping", "collapse_damping", "rest_fraction", "rest_hold", "headroom",
                      "settle_until_ek" } do
    if type(o[k]) ~= "number" or o[k] < 0 then error("collapse.run: " .. k .. " must be a number >= 0", 3) end
  end
  local n = o.width / o.cell
  if math.abs(n - math.floor(n + 0.5)) > 1e-6 then
    error(string.format("collapse.run: width %g is not a whole number of cells of %g", o.width, o.cell), 3)
  end
  return o
end

--- L_x = floor(max_x / l_cell + 1) l_cell (000, Eq. 70), the column width
-- counting every cell that holds a particle; the left wall is at x = 0.
function M.Lx(max_x, cell)
  return math.floor(max_x / cell + 1) * cell
end

--- Two fronts of the bulk of a deposit, beside Eq. 70's furthest particle,
-- which a tail of single particles sliding along the floor sets: the x below
-- which `fraction` of the mass lies, and the end of the material connected to
-- the left wall at x = 0, the left side of the first cell column without a
-- particle. xs and ms: the particles' x and masses (arrays of one length).
function M.bulk_fronts(xs, ms, cell, fraction)
  local order, total, occupied = {}, 0, {}
  for i = 1, #xs do
    order[i] = i
    total = total + ms[i]
    occupied[math.floor(xs[i] / cell)] = true
  end
  table.sort(order, function(a, b) return xs[a] < xs[b] end)
  local x_mass, sum = xs[order[#order]], 0
  for _, i in ipairs(order) do
    sum = sum + ms[i]
    if sum >= fraction * total * (1 - 1e-12) then x_mass = xs[i]; break end
  end
  local c = 0
  while occupied[c] do c = c + 1 end
  return x_mass, c * cell
end

--- t~ = t / sqrt(AR L_x^init / g) (000, Eq. 73).
function M.t_tilde(t, aspect_ratio, width, g)
  return t / math.sqrt(aspect_ratio * (width or 1) / (g or 9.81))
end

--- The final normalised runout of Lube et al. (2005) for planar collapses:
-- (L_f - L_i) / L_i = 1.2 a for a < 1.8 and 1.9 a^(2/3) for a > 2.8. Between
-- the two regimes both laws are returned (low, high). Also returns the final
-- height H_f / L_i (a for a < 1.15, a^0.4 above) and the arrest time in units
-- of sqrt(H_i / g), about 3 (so it compares with t~ of Eq. 73).
-- (VALIDATION.md; the prefactors are Lube et al.'s, to 20 %.)
function M.lube(a)
  local lin, pow = 1.2 * a, 1.9 * a ^ (2 / 3)
  local lo, hi
  if a < 1.8 then lo, hi = lin, lin
  elseif a > 2.8 then lo, hi = pow, pow
  else lo, hi = math.min(lin, pow), math.max(lin, pow) end
  local height = a < 1.15 and a or a ^ 0.4
  return { runout = 0.5 * (lo + hi), runout_low = lo, runout_high = hi, height = height, t_arrest = 3.0 }
end

--- The final normalised runout of Lajeunesse et al. (2005), glass beads in a
-- rectangular channel (quasi-2D), the experiments 000 §5.4 compares with:
-- Delta L / L_i = 1.2 a for a below about 2.3 and 1.9 a^(2/3) above (the law
-- as Kumar (2015, PhD thesis, Cambridge, ch. 2) quotes it from the paper).
function M.lajeunesse(a)
  return a < 2.3 and 1.2 * a or 1.9 * a ^ (2 / 3)
end

--- Write rows (arrays of numbers) under a header to a CSV file in the output
-- directory (a relative path) or at an absolute path. Returns the path.
M.write_csv = results.write_csv

local function sanitize(s)
  return (tostring(s):gsub("[^%w%.%-]", "_"))
end

local function dt_policy(o)
  if o.dt_policy then return o.dt_policy end
  if o.dt then return { fixed = o.dt } end
  return { a_tau = o.a_tau }
end

local function vtk_output(o, series)
  if not o.vtk then return nil end
  local v = type(o.vtk) == "table" and o.vtk or {}
  local out = { vtk = series, every = v.every or 0.05 }
  if v.fields then out.fields = v.fields end
  if v.format then out.format = v.format end
  return out
end

-- P-wave speed sqrt((K + 4G/3) / rho), for the column's period 4 H / c_p
local function p_wave_speed(o)
  local E, nu = o.E, o.nu
  local M_mod = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))
  return math.sqrt(M_mod / o.density)
end

--- Mean vertical stress in a band of one cell around mid-height of a settled
-- column and the lithostatic value -rho g (H - Y) it should equal, Y the
-- particles' initial heights (000 Fig. 13). Returns sigma, expected, error.
function M.mid_height_stress(sim, height, density, g, band)
  local u = sim:field("displacement")
  local s = sim:field("stress")
  local sum, ref, n = 0, 0, 0
  for i = 1, sim:particle_count() do
    local y = sim:particle(i).x[2]
    local y0 = y - u[3 * (i - 1) + 2]
    if math.abs(y0 - 0.5 * height) <= band then
      sum = sum + s[6 * (i - 1) + 2]
      ref = ref - density * g * (height - y0)
      n = n + 1
    end
  end
  if n == 0 then return nil end
  return sum / n, ref / n, math.abs(sum - ref) / math.abs(ref)
end

-- H, the column's height, and the grid's height above it (000, Eq. 58)
local function heights(o)
  local H = o.aspect_ratio * o.width
  return H, (math.ceil(H / o.cell - 1e-9) + o.headroom) * o.cell
end

-- the simulation of one phase ("settle" or "collapse") on a grid `width` wide;
-- the phases differ only in width, transfer and damping
local function phase_sim(o, phase, width, transfer, damping)
  local _, Hmesh = heights(o)
  return mpm.simulation{
    dim = 2, grid = { origin = { 0, 0 }, size = { width, Hmesh }, cell = o.cell }, gravity = { 0, -o.g },
    shape = o.shape, shape_boundary = o.shape_boundary,
    scheme = { transfer = transfer, stress_update = o.stress_update, holds = o.holds, volumetric = o.volumetric },
    dt = dt_policy(o), damping = { cundall = damping },
    boundary = { left = "slip", right = "slip", bottom = { "friction", mu = o.friction }, top = "free" },
    thermo = o.thermo, diagnostics = o.diagnostics and (o.name .. "_" .. phase .. ".csv") or false,
    diagnostics_every = o.diagnostics_every, name = o.name .. "_" .. phase,
    output = vtk_output(o, o.name .. "_" .. phase),
    split = phase == "collapse" and o.split or nil,
  }
end

local function settle_phase(o)
  local W, l = o.width, o.cell
  local H = heights(o)
  local elastic = mpm.material.linear_elastic{ density = o.density, E = o.E, nu = o.nu, name = "settling" }
  local s0 = o.initial_stress
  local sim = phase_sim(o, "settle", W, o.settle_strategy or o.strategy, o.damping)
  sim:add_particles(mpm.box{ min = { 0, 0 }, max = { W, H } },
                    { material = elastic, per_axis = o.per_axis, stress = { s0, s0, s0, 0, 0, 0 } })
  local e0 = sim:energy()
  -- settle until E_k stays below settle_until_ek of its peak over two periods
  -- of the column's first mode (4 H / c_p): E_k passes through zero twice a
  -- period, so a single small value proves nothing
  local period = 4 * H / p_wave_speed(o)
  local window = 2 * period
  local t_max = o.settle_time or 40 * period + 0.2
  local peak, hist = 0, {}
  local function settled(s)
    local t, ek = s:time(), s:energy().kinetic
    if ek > peak then peak = ek end
    hist[#hist + 1] = { t, ek }
    while hist[1][1] < t - window do table.remove(hist, 1) end
    if t < window or peak == 0 or o.settle_until_ek == 0 then return false end
    for _, h in ipairs(hist) do
      if h[2] >= o.settle_until_ek * peak then return false end
    end
    return true
  end
  sim:run{ time = t_max, stop_when = settled }
  local e1 = sim:energy()
  local sigma, expected, err = M.mid_height_stress(sim, H, o.density, o.g, l)
  local info = {
    time = sim:time(), steps = sim:step(), ek_peak = peak, ek_final = e1.kinetic,
    reached = sim:time() < t_max - 1e-12,
    drop = math.abs((e1.gravity + e1.elastic) - (e0.gravity + e0.elastic)),
    W_MPM = e1.mpm_error, W_damping = e1.damping,
    sigma_mid = sigma, sigma_lithostatic = expected, sigma_error = err,
  }
  return sim, info
end

local function default_name(o)
  o.name = o.name or string.format("AR%g_%s", o.aspect_ratio, sanitize(o.strategy))
  return o
end

--- The settling phase alone, with the options of collapse.run (those of the
-- collapse are ignored). Returns the settled simulation, not saved, and a
-- table: time, steps, reached (E_k criterion met before settle_time),
-- ek_peak, ek_final, drop (|Delta E_g + Delta E_el|), W_MPM, W_damping,
-- sigma_mid, sigma_lithostatic and sigma_error (000 Fig. 13).
function M.settle(opts)
  return settle_phase(default_name(check_options(opts)))
end

local SERIES_HEADER = { "time", "t_tilde", "max_x", "L_x", "d_r", "L_tilde", "height", "E_kinetic", "E_gravity",
                        "E_elastic", "W_plastic", "W_friction", "W_damping", "W_MPM" }

-- the settling, saved to a checkpoint (or the one given as `settled`); its path
local function settled_checkpoint(o, result)
  if o.settled then return o.settled end
  local ssim, info = settle_phase(o)
  result.settle = info
  local path = ssim:save(o.name .. "_settled.h5")
  if o.keep then result.settle_sim = ssim else ssim:free() end
  return path
end

-- the settled particles on a grid width_factor times wider, as Mohr-Coulomb sand
-- (or as the material given)
local function collapse_sim(o, settled)
  local sand = o.material or mpm.material.mohr_coulomb{ density = o.density, E = o.E, nu = o.nu, phi = o.phi,
                                                        psi = o.psi, cohesion = o.cohesion, tension = o.tension,
                                                        name = "sand" }
  local sim = phase_sim(o, "collapse", o.width_factor * o.width, o.strategy, o.collapse_damping)
  sim:import(settled, { material = sand })
  return sim
end

-- The particles' positions as initial position + displacement, so that a
-- sample costs one field call instead of one sim:particle() per particle.
-- Particle splitting (option `split`) adds particles and moves the initial
-- position of those it splits: the initial positions are read again
-- whenever the count changed.
-- Returns a table: extent() (the largest x and y) and xs() (every x).
local function positions(sim)
  local n, base = -1, {}
  local function refresh()
    if sim:particle_count() == n then return end
    n = sim:particle_count()
    local u = sim:field("displacement")
    for i = 1, n do
      local x = sim:particle(i).x
      base[2 * i - 1] = x[1] - u[3 * i - 2]
      base[2 * i] = x[2] - u[3 * i - 1]
    end
  end
  local p = {}
  function p.extent()
    refresh()
    local u = sim:field("displacement")
    local mx, my = -math.huge, -math.huge
    for i = 1, n do
      local x = base[2 * i - 1] + u[3 * i - 2]
      local y = base[2 * i] + u[3 * i - 1]
      if x > mx then mx = x end
      if y > my then my = y end
    end
    return mx, my
  end
  function p.xs()
    refresh()
    local u, xs = sim:field("displacement"), {}
    for i = 1, n do xs[i] = base[2 * i - 1] + u[3 * i - 2] end
    return xs
  end
  return p
end

-- The series of the collapse (columns SERIES_HEADER) and the peak of E_k:
-- st.sample(sim) adds the row of the current time, once per time.
local function series(o, pos, Lx0, tscale)
  local W, l = o.width, o.cell
  local st = { cols = {}, peak = 0, t_peak = 0 }
  for _, h in ipairs(SERIES_HEADER) do st.cols[h] = {} end
  local last_t = -1
  function st.sample(s)
    local t = s:time()
    if t == last_t then return end
    last_t = t
    local mx, my = pos.extent()
    local Lx = M.Lx(mx, l)
    local e = s:energy()
    local row = { t, t / tscale, mx, Lx, Lx - Lx0, (Lx - Lx0) / Lx0, my / W, e.kinetic, e.gravity, e.elastic,
                  e.plastic, e.friction, e.damping, e.mpm_error }
    for k, h in ipairs(SERIES_HEADER) do local c = st.cols[h]; c[#c + 1] = row[k] end
    if e.kinetic > st.peak then st.peak, st.t_peak = e.kinetic, t end
  end
  return st
end

-- with stop_at_rest: stop once E_k stayed below rest_fraction of its peak for rest_hold s
local function rest_stop(o, st)
  if not o.stop_at_rest then return nil end
  local since
  return function(s)
    local ek = s:energy().kinetic
    if ek > st.peak then st.peak, st.t_peak = ek, s:time() end
    if st.peak > 0 and ek < o.rest_fraction * st.peak and s:time() > st.t_peak then
      since = since or s:time()
      return s:time() - since >= o.rest_hold
    end
    since = nil
    return false
  end
end

-- t_rest, t_rest_tilde and t_final_Lx from the last sample of the series backwards
local function rest_times(result, o, st, tscale)
  local cols, k = st.cols, #st.cols.time
  local t_rest
  for j = k, 1, -1 do
    if cols.E_kinetic[j] >= o.rest_fraction * st.peak or cols.time[j] <= st.t_peak then break end
    t_rest = cols.time[j]
  end
  result.t_rest = t_rest
  result.t_rest_tilde = t_rest and t_rest / tscale
  for j = k, 1, -1 do
    if cols.L_x[j] ~= result.L_x then break end
    result.t_final_Lx = cols.time[j]
  end
end

-- the measures of the deposit at the end of the collapse into result
local function final_measures(result, o, sim, st, pos, e0, tscale)
  local l, cols = o.cell, st.cols
  local k = #cols.time
  local Lx0 = result.L_x_init
  local e1 = sim:energy()
  result.L_x = cols.L_x[k]
  result.d_r = cols.d_r[k]
  result.runout = cols.L_tilde[k]
  result.max_x = cols.max_x[k]
  result.height = cols.height[k]
  -- the column reached the right wall of the grid: the runout is capped
  result.at_wall = result.max_x > o.width_factor * o.width - l
  result.time = sim:time()
  result.steps = sim:step()
  result.particles = sim:particle_count() -- more than at the start with `split`
  result.ek_peak, result.t_peak, result.ek_final = st.peak, st.t_peak, e1.kinetic
  rest_times(result, o, st, tscale)
  local x_mass, x_conn = M.bulk_fronts(pos.xs(), sim:field("mass"), l, o.bulk_fraction)
  result.runout_mass = (M.Lx(x_mass, l) - Lx0) / Lx0
  result.runout_connected = (x_conn - Lx0) / Lx0
  result.dEp_stable = math.abs((e1.gravity + e1.elastic) - (e0.gravity + e0.elastic))
  result.W_MPM = e1.mpm_error
  result.W_MPM_ratio = result.dEp_stable > 0 and math.abs(e1.mpm_error) / result.dEp_stable or nil
  result.energy = e1
  result.ek_start = e0.kinetic
  local eps = sim:field("eps_D")
  local emax = 0
  for i = 1, #eps do if eps[i] > emax then emax = eps[i] end end
  result.eps_D_max = emax
  result.series = cols
end

-- <name>_series.csv: one row per sample
local function write_series(o, cols)
  local rows = {}
  for j = 1, #cols.time do
    local r = {}
    for c, h in ipairs(SERIES_HEADER) do r[c] = cols[h][j] end
    rows[j] = r
  end
  return M.write_csv(o.name .. "_series.csv", SERIES_HEADER, rows)
end

-- result:at(t_tilde) and result:t_tilde_at_front(d)
local function add_lookups(result)
  function result:at(t_tilde)
    local c = self.series
    local j = 1
    while j < #c.t_tilde and c.t_tilde[j + 1] <= t_tilde + 1e-12 do j = j + 1 end
    local s = {}
    for _, h in ipairs(SERIES_HEADER) do s[h] = c[h][j] end
    s.front = c.max_x[j] - self.max_x_init   -- front advance, m (not quantised)
    return s
  end
  -- the first sampled t~ at which the front had advanced by d metres (nil if never)
  function result:t_tilde_at_front(d)
    local c = self.series
    for j = 1, #c.max_x do
      if c.max_x[j] - self.max_x_init >= d then return c.t_tilde[j] end
    end
    return nil
  end
end

--- Runs the settling and the collapse; returns a result table:
--   runout       final L~ (000, Eq. 72)
--   L_x, d_r     final column width and runout, m (000, Eqs. 70-71)
--   L_x_init     initial column width by Eq. 70, m
--   runout_mass  L~ of the bulk: Eq. 70 applied to the x below which
--                bulk_fraction of the mass lies instead of the furthest particle
--   runout_connected  L~ of the deposit connected to the left wall (up to the
--                first cell column without a particle); see M.bulk_fronts
--   height       final height of the column / width
--   at_wall      true when the front reached the last cell before the right
--                wall: the runout is then capped by the grid
--   t_rest       s, first time from which E_k stays below rest_fraction of its
--                peak to the end (nil if never); t_rest_tilde the same in t~
--   t_final_Lx   s, first time the column reached its final L_x
--   ek_peak, t_peak, ek_final
--   dEp_stable   |Delta E_g + Delta E_el| over the collapse, J/m (000, Eq. 69)
--   W_MPM        the energy error at the end, J/m (000, Eq. 68)
--   W_MPM_ratio  |W_MPM| / dEp_stable
--   energy       sim:energy() at the end
--   eps_D_max    the largest deviatoric strain (000, Eq. 75)
--   settle       the settling: time, steps, ek_peak, ek_final, drop, W_MPM,
--                sigma_error (vertical stress at mid-height vs lithostatic)...
--   series       columns time, t_tilde, max_x, L_x, d_r, L_tilde, height,
--                E_kinetic, ... W_MPM (each a list), sampled every sample_every
--   files        paths written (series, settled, ...)
--   settle_sim, collapse_sim  with keep = true
-- result:at(t_tilde) gives the sample at the last t~ <= t_tilde (with
-- `front`, the advance of the furthest particle, m), and
-- result:t_tilde_at_front(d) the first t~ at which the front had moved d m.
function M.run(opts)
  local o = default_name(check_options(opts))
  local W, l, ar = o.width, o.cell, o.aspect_ratio
  local result = { aspect_ratio = ar, strategy = o.strategy, stress_update = o.stress_update, cell = l,
                   per_axis = o.per_axis, width = W, name = o.name, files = {} }
  -- 1. settling, saved to a checkpoint
  local settled = settled_checkpoint(o, result)
  result.files.settled = settled
  -- 2. collapse on a wider grid, Mohr-Coulomb
  local sim = collapse_sim(o, settled)
  if o.vtk then result.files.vtk = { settle = o.name .. "_settle.pvd", collapse = o.name .. "_collapse.pvd" } end
  local pos = positions(sim)
  local mx0 = pos.extent()
  local Lx0 = M.Lx(mx0, l)
  local e0 = sim:energy()
  local tscale = math.sqrt(ar * W / o.g)
  local st = series(o, pos, Lx0, tscale)
  sim:hook{ every_time = o.sample_every, fn = st.sample }
  sim:run{ time = o.collapse_time or 8 * tscale, stop_when = rest_stop(o, st) }
  st.sample(sim)
  -- results
  result.L_x_init = Lx0
  result.max_x_init = mx0
  final_measures(result, o, sim, st, pos, e0, tscale)
  result.time_scale = tscale
  if o.csv then result.files.series = write_series(o, st.cols) end
  if o.keep then result.collapse_sim = sim else sim:free() end
  add_lookups(result)
  return result
end

--- A one-line summary of a result.
function M.summary(r)
  return string.format("AR %-4g %-8s L~ = %.2f (L_x = %.2f m; bulk %.2f, connected %.2f)  t_rest = %s s (t~ %s)  " ..
                       "|W_MPM|/|dEp| = %.2e  dEp = %.4g J/m  H_f/L = %.2f",
                       r.aspect_ratio, r.strategy, r.runout, r.L_x, r.runout_mass, r.runout_connected,
                       r.t_rest and string.format("%.2f", r.t_rest) or "-",
                       r.t_rest_tilde and string.format("%.2f", r.t_rest_tilde) or "-",
                       r.W_MPM_ratio or 0, r.dEp_stable, r.height)
end

return M

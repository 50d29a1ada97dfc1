-- moraine fuzzing: decode bytes into a sequence of deck API calls.
--
-- Loaded by tests/fuzz/fuzz_deck.c; returns function(bytes, specs, outdir).
-- `specs` maps each option group ("simulation{}", "simulation{} grid",
-- "run{}", ...) to its list of {key, type}, straight from the engine. Every
-- call runs under pcall: an error is a correct answer to a bad call, only a
-- crash or a sanitizer report counts. Values come from small pools so that
-- most grids and particle counts stay small (a fuzzing run should try many
-- calls, not one big simulation), with the hostile values mixed in.
local mpm = require "moraine"

-- MORAINE_FUZZ_TRACE=1 prints what every call answered (for looking at a corpus)
local trace = os.getenv("MORAINE_FUZZ_TRACE")
local raw_pcall = pcall
local function pcall(f, ...)
  local r = table.pack(raw_pcall(f, ...))
  if trace then io.stderr:write(string.format("  %s %s\n", r[1] and "ok " or "err", tostring(r[2]))) end
  return table.unpack(r, 1, r.n)
end

return function(bytes, specs, outdir)
  local pos, n = 1, #bytes
  local function u8()
    if pos > n then return 0 end
    local b = bytes:byte(pos)
    pos = pos + 1
    return b
  end
  local function pick(list) return list[u8() % #list + 1] end

  local sims, materials, regions = {}, {}, {}
  local depth = 0 -- callbacks that call the API again are allowed, a few levels deep

  -- numbers a deck could plausibly hold, then hostile ones
  local nice = { 0.1, 0.25, 0.5, 1, 2, 0.3, 0.2, 0.05, 3, 1e-3, 1e6, 1000, 2000, 30, 0.4, 0.75 }
  local hostile = { 0, -0.0, -1, -0.1, 0 / 0, 1 / 0, -1 / 0, 1e308, -1e308, 5e-324, 1e-300, 2 ^ 53,
                    math.maxinteger, math.mininteger, 0.5, 1 - 1e-16, 90, 91, 45, 89.999, -90, 1e9, 7.5,
                    2 ^ 31, -2 ^ 31, 64, 65, 513, 1e15 }
  local function number()
    local b = u8()
    if b < 160 then return nice[b % #nice + 1] end
    if b < 240 then return hostile[b % #hostile + 1] end
    return (b - 240) / 4 -- 0 .. 3.75
  end
  local function integer()
    local b = u8()
    if b < 200 then return b % 5 end
    return hostile[b % #hostile + 1]
  end

  local names = { "linear", "gimp", "quadratic_bspline", "cubic_bspline", "FLIP", "PIC", "APIC", "TPIC",
                  "XPIC", "USF", "USL", "MUSL", "USAVG", "free", "fixed", "slip", "friction", "velocity",
                  "periodic", "standard", "mls", "gauss", "regular", "binary", "ascii", "plain", "affine",
                  "taylor", "blend", "grid", "particle", "x", "v", "stress", "strain", "mass", "vol", "id",
                  "material", "F", "J", "sum", "min", "max", "mean", "", "frction", "quadratic", "flip",
                  "\0", "a\nb", string.rep("z", 300), "out", "ck", "series", "%s%n", "..", "/" }
  local function str() return pick(names) end

  -- files stay inside the fuzzing directory, except names that cannot be written
  local function path()
    local b = u8()
    if b < 200 then return outdir .. "/" .. pick({ "a.h5", "b.h5", "c.h5", "sub/d.h5", "e" }) end
    return pick({ "", outdir, "/nonexistent/dir/x.h5", outdir .. "/", "/proc/self/status", outdir .. "/\0x" })
  end

  local value -- forward
  local dim = 2 -- of the last simulation made: vectors mostly have this many components
  local function vector()
    local len = u8() % 8
    if len > 4 then len = dim end
    local t = {}
    for i = 1, len do t[i] = number() end
    return t
  end

  local function keys_of(group) return specs[group] or {} end

  -- a table of options for one group: some known keys, maybe a misspelt or a positional one
  local function options(group)
    local t = {}
    local list = keys_of(group)
    local count = u8() % 6
    for _ = 1, count do
      if #list == 0 then break end
      local s = pick(list)
      t[s.key] = value(group, s)
    end
    local extra = u8()
    if extra >= 240 and #list > 0 then
      local k = pick(list).key
      t[k:sub(2) .. k:sub(1, 1)] = number() -- a typo
    elseif extra >= 230 then
      t[#t + 1] = number() -- a positional value
    elseif extra >= 225 then
      t[str()] = value()
    end
    return t
  end

  local function material()
    if #materials > 0 and u8() < 200 then return pick(materials) end
    local models = {}
    for k in pairs(mpm.material) do
      if type(mpm.material[k]) == "function" then models[#models + 1] = k end
    end
    table.sort(models)
    local model = pick(models)
    -- mostly a clean, valid set so that particles get made; else random options
    local opts
    if u8() < 160 then
      opts = model == "newtonian" and { density = 1000, viscosity = 1e-3, sound_speed = 10 }
          or { density = pick({ 1000, 2000 }), E = pick({ 1e5, 1e6 }), nu = pick({ 0.2, 0.3 }) }
    else
      opts = options("material." .. model .. "{}")
    end
    local ok, m = pcall(mpm.material[model], opts)
    if ok then materials[#materials + 1] = m end
    return ok and m or opts
  end

  -- a box inside the usual small grid
  local function small_box()
    local lo, hi = {}, {}
    for i = 1, dim do
      lo[i] = pick({ 0.1, 0.15, 0.2 })
      hi[i] = lo[i] + pick({ 0.05, 0.1, 0.2 })
    end
    return mpm.box { min = lo, max = hi }
  end
  local plain = mpm.material.linear_elastic { density = 1000, E = 1e6, nu = 0.3 }

  local function region()
    if #regions > 0 and u8() < 128 then return pick(regions) end
    local kind = u8() % 16
    local ok, r
    if kind == 0 then ok, r = pcall(mpm.box, options("box{}"))
    elseif kind == 1 then ok, r = pcall(mpm.box, { min = vector(), max = vector() })
    elseif kind == 2 then ok, r = pcall(mpm.disk, options("disk{} / sphere{}"))
    elseif kind == 3 then ok, r = pcall(mpm.sphere, { center = vector(), radius = number() })
    elseif kind == 4 then ok, r = pcall(mpm.cylinder, { from = vector(), to = vector(), radius = number() })
    elseif kind == 5 then
      local vs = {}
      for i = 1, u8() % 6 do vs[i] = vector() end
      ok, r = pcall(mpm.polygon, { vertices = vs })
    elseif kind == 6 then ok, r = pcall(mpm.region, value())
    elseif kind == 7 then
      local f = pick({ mpm.union, mpm.difference, mpm.intersection })
      ok, r = pcall(f, value(), value(), value())
    else
      ok, r = pcall(small_box)
    end
    if ok then regions[#regions + 1] = r end
    return ok and r or nil
  end

  local function callback()
    local behaviour = u8() % 6
    return function(...)
      if behaviour == 0 then return number() end
      if behaviour == 1 then error("deck callback error") end
      if behaviour == 2 then return str() end
      if behaviour == 3 and depth < 3 then
        depth = depth + 1
        local act = u8()
        local s = sims[#sims]
        if s then pcall(function() if act % 3 == 0 then s:run { steps = 1 } elseif act % 3 == 1 then s:free() else s:step() end end) end
        depth = depth - 1
        return true
      end
      if behaviour == 4 then return nil end
      return u8() % 2 == 0
    end
  end

  -- a plausible value for each option type
  local by_type = { number = number, integer = integer, vector = vector, string = str, ["function"] = callback,
                    boolean = function() return u8() % 2 == 0 end }

  -- a value for a key of a group; plausible for its type most of the time
  value = function(group, spec)
    local b = u8()
    if spec and b < 200 then
      local sub = group and specs[group .. " " .. spec.key]
      if spec.key == "boundary" then
        local t = {}
        for _ = 1, u8() % 4 do
          local face = pick(keys_of("simulation{} boundary"))
          t[face.key] = (u8() % 2 == 0) and str() or options("boundary face")
        end
        return t
      elseif sub then
        return options(group .. " " .. spec.key)
      elseif spec.key == "output" then
        return options("simulation{} output")
      elseif spec.key == "material" then
        return material()
      elseif spec.key == "region" then
        return region()
      elseif by_type[spec.type] then
        return by_type[spec.type]()
      end
    end
    local kind = b % 12
    if kind == 0 then return number()
    elseif kind == 1 then return integer()
    elseif kind == 2 then return str()
    elseif kind == 3 then return u8() % 2 == 0
    elseif kind == 4 then return nil
    elseif kind == 5 then return vector()
    elseif kind == 6 then return callback()
    elseif kind == 7 then return #sims > 0 and pick(sims) or {}
    elseif kind == 8 then return #materials > 0 and pick(materials) or {}
    elseif kind == 9 then return #regions > 0 and pick(regions) or {}
    elseif kind == 10 then return options(pick({ "simulation{}", "run{}", "simulation{} grid" }))
    else return { {}, { 1, 2 }, "x" } end
  end

  local function simulation()
    local opts = options("simulation{}")
    if u8() < 220 then
      -- a small grid most of the time
      opts.dim = opts.dim or (u8() % 2 == 0 and 2 or 3)
      opts.grid = opts.grid or { size = { 0.5, 0.5, 0.5 }, cell = pick({ 0.1, 0.125, 0.25 }) }
      if type(opts.grid) == "table" and type(opts.grid.size) == "table" then
        for i = #opts.grid.size, (opts.dim == 3 and 4 or 3), -1 do opts.grid.size[i] = nil end
      end
      opts.thermo = opts.thermo or 0
      opts.progress = false
      if u8() < 200 then opts.diagnostics = false end
      if u8() < 200 then opts.series = false end
    end
    -- A legal but huge grid (more than 200 cells along an axis, up to the
    -- engine's own limits) is not a finding, only slow and memory-hungry:
    -- its cell is made coarser. Grids beyond the limits are left to be refused.
    local g = opts.grid
    if type(g) == "table" and type(g.cell) == "number" and type(g.size) == "table" then
      for _, len in ipairs(g.size) do
        if type(len) == "number" and len / g.cell > 200 and len / g.cell <= 1e6 then g.cell = len / 8 end
      end
    end
    local ok, s = pcall(mpm.simulation, opts)
    if ok then
      sims[#sims + 1] = s
      dim = s:dim()
    end
  end

  local function sim() return #sims > 0 and pick(sims) or nil end

  -- one method call with arguments from the input
  local methods = {
    function(s) return s:add_particles(region(), options("add_particles()")) end,
    function(s) return s:add_particles(region(), { material = material(), per_axis = u8() % 3 + 1 }) end,
    function(s) return s:add_particles(small_box(), { material = u8() < 128 and plain or material() }) end,
    function(s) return s:add_particles(small_box(), { material = plain, velocity = vector() }) end,
    function(s)
      local o = options("run{}")
      if u8() < 230 then o.steps = o.steps or (u8() % 3 + 1) end
      o.progress = false
      return s:run(o)
    end,
    function(s) return s:hook(options("hook{}")) end,
    function(s) return s:set_gravity(vector()) end,
    function(s) return s:set_boundary(value("simulation{}", { key = "boundary", type = "table" })) end,
    function(s) return s:set_scheme(u8() % 2 == 0 and str() or options("simulation{} scheme")) end,
    function(s) return s:set_dt(u8() % 2 == 0 and number() or options("simulation{} dt")) end,
    function(s) return s:constrain(options("constrain{}")) end,
    function(s) return s:reaction(integer()) end,
    function(s) return s:set_constraint(integer(), { vx = number(), vy = number(), vz = number() }) end,
    function(s) return s:save(path()) end,
    function(s)
      local ok, loaded = pcall(mpm.load, path(), u8() % 2 == 0 and options("load()") or nil)
      if ok and loaded then sims[#sims + 1] = loaded end
    end,
    function(s) return s:import(path(), { material = u8() % 2 == 0 and material() or nil, offset = vector() }) end,
    function(s) return s:set_damping(options("simulation{} damping")) end,
    function(s) return s:dt_estimate() end,
    function(s) return s:output(options("simulation{} output")) end,
    function(s) return s:write_vtk() end,
    function(s) return s:time(), s:dt(), s:particle_count(), s:dim(), s:energy(), s:diagnostics(), s:info() end,
    function(s) return s:step() end,
    function(s) return s:field(str()) end,
    function(s) return s:record(str(), value()) end,
    function(s) return s:reduce(str(), str(), u8() % 2 == 0 and { region = region() } or value()) end,
    function(s) return s:particle(integer()) end,
    function(s) return tostring(s) end,
    function(s) return s:free() end,
  }
  local helpers = {
    function() return mpm.param(str(), value()) end,
    function() return mpm.dt.fixed(number(), u8() % 2 == 0 and options("simulation{} dt") or nil) end,
    function() return mpm.dt.a_tau(number()) end,
    function() return mpm.rigid_rotation(options("simulation{}")) end,
    function() return mpm.lithostatic { sim = sim(), material = material(), surface = number(), k0 = number() } end,
    function() return region() and regions[#regions]:contains(number(), number(), number()) end,
    function() return material() end,
    function() collectgarbage() end,
  }

  for _ = 1, 64 do
    if pos > n then break end
    local op = u8()
    if op < 40 or #sims == 0 then
      simulation()
    elseif op < 220 then
      local s = sim()
      pcall(pick(methods), s)
    else
      pcall(pick(helpers))
    end
  end
  -- close what is left, in an order chosen by the input
  for i = #sims, 1, -1 do
    if u8() % 2 == 0 then pcall(sims[i].free, sims[i]) end
  end
end

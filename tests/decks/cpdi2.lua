-- CPDI2 (shape = "cpdi2", doc/numerics.md "CPDI2") on two cases (--set
-- part=bar or part=vortex picks one; default both):
--
-- bar: cpdi.lua's tension bar (tension_bar.lua) pulled to 3 times its
-- length with CPDI2: the uniform stretch keeps the tracked quadrilaterals
-- parallelograms, so CPDI2 must do what CPDI does there. Asserted with PIC,
-- FLIP and APIC: no cell of the bar's middle rows left unreached by a
-- particle's quadrilateral (its bounding box), F_xx within [2, 4] away from
-- the grips (exact: 3), mass to 1e-12, the bar 3 L0 long.
--
-- vortex: a soft block filling a doubly periodic square, started with the
-- cellular velocity field v = U (sin kx cos ky, -cos kx sin ky), two
-- wavelengths across, and left to move (its stress stays negligible, so
-- each particle keeps its velocity): the map X -> X + t v(X) bends each
-- particle's domain, since its mixed second derivative t d2v/dXdY is not
-- zero. Seeded regularly, the domains tile the block at the start, and
-- four domains meet at each inner corner. Measured: the four copies of each
-- such corner, one per domain, after 0.2 s (t |grad v| up to 0.63): their
-- largest distance from their mean (in units of the domains' initial
-- half-width r), the gaps and overlaps between neighbouring domains. CPDI
-- forms each parallelogram from its particle's F, and the four disagree
-- by about r^2 |d2x/dXdY|; CPDI2's corners move with the grid velocity,
-- which is continuous, so the copies stay together up to the recentring on
-- the particles. Asserted with PIC, FLIP and APIC: CPDI2's mean and largest
-- mismatch at most a quarter and a half of CPDI's, and CPDI's mean at
-- least 0.003 r (the case tells them apart). Reported: how far each
-- quadrilateral's area is from the particle's volume J vol0 (the volume
-- the stress uses). And a CPDI2 run saved half-way, loaded and run on ends
-- bit for bit where the straight run does, corners included.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local part = mpm.param("part", "")

if part == "" or part == "bar" then
  local B = dofile(mpm.deck_dir .. "/tension_bar.lua")
  for _, scheme in ipairs{ "APIC", "FLIP", "PIC" } do
    local r = B.run(T, "cpdi2", scheme, "corners")
    local id = "cpdi2_tension_bar." .. scheme
    T.expect{ id = id .. ".unreached", value = r.unreached, max = 0,
              what = "CPDI2 + " .. scheme .. ": cells of the bar unreached by a particle domain at 3 L0" }
    T.expect{ id = id .. ".fxx_min", value = r.fxx_min, min = 2, what = "CPDI2 + " .. scheme .. ": smallest F_xx (exact 3)" }
    T.expect{ id = id .. ".fxx_max", value = r.fxx_max, max = 4, what = "CPDI2 + " .. scheme .. ": largest F_xx (exact 3)" }
  end
end

if part == "" or part == "vortex" then
  local CELL, L, U, K = 0.05, 1.0, 0.25, 4 * math.pi
  local R = 0.25 * CELL -- the domains' initial half-width: 2 particles per cell and axis
  local SIGNS = { { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } } -- the corners, counter-clockwise
  local duration = mpm.param("time", 0.2)
  local function velocity(x, y) return U * math.sin(K * x) * math.cos(K * y), -U * math.cos(K * x) * math.sin(K * y) end
  local function wrap(d) return d - L * math.floor(d / L + 0.5) end

  -- the corners shared at the start: the key of each corner's position, and
  -- the (particle, corner) pairs at it
  local function shared_corners(sim)
    local groups, keys, m = {}, {}, math.floor(L / R + 0.5)
    for i = 1, sim:particle_count() do
      local x = sim:particle(i).x
      for c, s in ipairs(SIGNS) do
        local key = (math.floor((x[1] + R * s[1]) / R + 0.5) % m) * m + math.floor((x[2] + R * s[2]) / R + 0.5) % m
        if not groups[key] then groups[key], keys[#keys + 1] = {}, key end
        table.insert(groups[key], { i, c })
      end
    end
    return groups, keys
  end

  -- corner c of particle i now: CPDI's parallelogram x_p + r F s_c, CPDI2's tracked corner
  local function corner_of(sim, shape)
    local pos, F, vol = sim:field("position"), sim:field("deformation_gradient"), sim:field("volume")
    local q = shape == "cpdi2" and sim:field("cpdi2_corners")
    return function(i, c)
      local x, y = pos[3 * i - 2], pos[3 * i - 1]
      if q then return x + q[8 * (i - 1) + 2 * c - 1], y + q[8 * (i - 1) + 2 * c] end
      local k, s = 9 * (i - 1), SIGNS[c]
      local fxx, fxy, fyx, fyy = F[k + 1], F[k + 2], F[k + 4], F[k + 5]
      local r = 0.5 * math.sqrt(vol[i] / (fxx * fyy - fxy * fyx))
      return x + r * (fxx * s[1] + fxy * s[2]), y + r * (fyx * s[1] + fyy * s[2])
    end
  end

  -- the largest |area / (J vol0) - 1| of the CPDI2 quadrilaterals (shoelace)
  local function area_gap(sim, corner)
    local vol, worst = sim:field("volume"), 0
    for i = 1, sim:particle_count() do
      local a = 0
      for c = 1, 4 do
        local x1, y1 = corner(i, c)
        local x2, y2 = corner(i, c % 4 + 1)
        a = a + 0.5 * (x1 * y2 - x2 * y1)
      end
      worst = math.max(worst, math.abs(a / vol[i] - 1))
    end
    return worst
  end

  local function build(shape, scheme, name)
    local sim = mpm.simulation{
      dim = 2, grid = { size = { L, L }, cell = CELL }, shape = shape, gravity = { 0, 0 }, scheme = scheme,
      dt = { fixed = 2.5e-3 }, thermo = 0, diagnostics = false, series = false, name = name,
      boundary = { left = "periodic", right = "periodic", bottom = "periodic", top = "periodic" },
    }
    sim:add_particles(mpm.box{ min = { 0, 0 }, max = { L, L } }, {
      material = mpm.material.neo_hookean{ density = 1000, E = 0.01, nu = 0.3 }, per_axis = 2,
      placement = "regular", velocity = velocity })
    return sim
  end

  local function run(shape, scheme)
    local sim = build(shape, scheme, shape .. "_" .. scheme)
    local groups, keys = shared_corners(sim)
    sim:run{ time = duration }
    local corner = corner_of(sim, shape)
    local worst, sum, count = 0, 0, 0
    for _, key in ipairs(keys) do
      local g = groups[key]
      local x0, y0 = corner(g[1][1], g[1][2])
      local pts, mx, my = {}, 0, 0
      for _, m in ipairs(g) do -- the copies about the first, across the periodic faces
        local x, y = corner(m[1], m[2])
        x, y = x0 + wrap(x - x0), y0 + wrap(y - y0)
        pts[#pts + 1] = { x, y }
        mx, my = mx + x / #g, my + y / #g
      end
      for _, p in ipairs(pts) do
        local d = math.sqrt((p[1] - mx) ^ 2 + (p[2] - my) ^ 2) / R
        worst, sum, count = math.max(worst, d), sum + d, count + 1
      end
    end
    local gap = shape == "cpdi2" and area_gap(sim, corner) or nil
    print(string.format("vortex %-5s %-4s: shared corners' mismatch mean %.4f r, largest %.4f r (%d copies)%s", shape,
                        scheme, sum / count, worst, count,
                        gap and string.format("; largest |area / (J vol0) - 1| %.2e", gap) or ""))
    sim:free()
    return { mean = sum / count, worst = worst, gap = gap }
  end

  for _, scheme in ipairs{ "APIC", "FLIP", "PIC" } do
    local one, two = run("cpdi", scheme), run("cpdi2", scheme)
    local id = "cpdi2_vortex." .. scheme
    T.expect{ id = id .. ".cpdi_mean", value = one.mean, min = 0.003, unit = "r",
              what = "CPDI + " .. scheme .. ": mean distance of a shared corner's copies from their mean" }
    T.expect{ id = id .. ".cpdi2_mean", value = two.mean, max = 0.25 * one.mean, unit = "r",
              what = "CPDI2 + " .. scheme .. ": the same (at most a quarter of CPDI's)" }
    T.expect{ id = id .. ".cpdi_worst", value = one.worst, unit = "r", asserted = false,
              what = "CPDI + " .. scheme .. ": largest distance of a shared corner's copy from their mean" }
    T.expect{ id = id .. ".cpdi2_worst", value = two.worst, max = 0.5 * one.worst, unit = "r",
              what = "CPDI2 + " .. scheme .. ": the same (at most half of CPDI's)" }
    T.expect{ id = id .. ".area", value = two.gap, asserted = false,
              what = "CPDI2 + " .. scheme .. ": largest |quadrilateral area / (J vol0) - 1|" }
  end

  -- the corners through a checkpoint: saved half-way, loaded, run on = the
  -- straight run, bit for bit
  local straight = build("cpdi2", "APIC", "straight")
  straight:run{ steps = 80 }
  local first = build("cpdi2", "APIC", "first")
  first:run{ steps = 40 }
  first:save("cpdi2_mid.h5")
  local loaded = mpm.load("cpdi2_mid.h5", { thermo = 0, diagnostics = false })
  loaded:run{ steps = 40 }
  for _, f in ipairs{ "velocity", "displacement", "deformation_gradient", "stress", "cpdi2_corners" } do
    local x, y = straight:field(f), loaded:field(f)
    T.check(#x == #y and #x > 0, "checkpoint: %s has %d values against %d", f, #y, #x)
    for i = 1, #x do
      if x[i] ~= y[i] then T.check(false, "checkpoint: %s[%d] differs: %.17g vs %.17g", f, i, x[i], y[i]) end
    end
  end
  print("vortex cpdi2 APIC: checkpoint at step 40, step 80 bit for bit with the straight run")
end
T.done("cpdi2")

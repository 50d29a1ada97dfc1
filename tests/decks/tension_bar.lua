-- The large-deformation tension bar shared by split_tension_bar.lua and
-- cpdi.lua: a soft elastic (neo-Hookean) bar 1 m long pulled to 3 times its
-- length by two heavy grips moving apart at 0.5 m/s; it starts with the
-- matching linear velocity profile, and its stress (E = 10 Pa) stays small
-- against its inertia (rho V^2 = 250 Pa), so the exact motion is the
-- uniform stretch F_xx = 3 at the end. 2 x 2 particles per cell of 0.025 m.
local B = { CELL = 0.025, L0 = 1.0, H = 0.1, V_END = 0.5 }
B.T_END = (3 - 1) * B.L0 / (2 * B.V_END) -- the grips 3 L0 apart (inner faces)
local bar = mpm.material.neo_hookean{ density = 1000, E = 10, nu = 0.3, name = "bar" }
local grip = mpm.material.neo_hookean{ density = 1e9, E = 10, nu = 0.3, name = "grip" }

-- opts: scheme, split (table or false), shape (default quadratic_bspline), name
function B.build(opts)
  local CELL, L0, H, V_END = B.CELL, B.L0, B.H, B.V_END
  local sim = mpm.simulation{
    dim = 2, grid = { origin = { -2, 0 }, size = { 4, 0.25 }, cell = CELL }, shape = opts.shape,
    scheme = opts.scheme, dt = { fixed = 2.5e-3 }, split = opts.split, thermo = 0, diagnostics = false,
    series = false, name = opts.name or (opts.split and "split_" or "standard_") .. opts.scheme,
  }
  local function velocity(x) return V_END * math.max(-1, math.min(1, x / (0.5 * L0))), 0 end
  sim:add_particles(mpm.box{ min = { -0.5 * L0, 0.075 }, max = { 0.5 * L0, 0.075 + H } },
                    { material = bar, per_axis = 2, velocity = velocity })
  local nbar = sim:particle_count()
  sim:add_particles(mpm.box{ min = { -0.5 * L0 - 0.1, 0.075 }, max = { -0.5 * L0, 0.075 + H } },
                    { material = grip, per_axis = 2, velocity = { -V_END, 0 } })
  sim:add_particles(mpm.box{ min = { 0.5 * L0, 0.075 }, max = { 0.5 * L0 + 0.1, 0.075 + H } },
                    { material = grip, per_axis = 2, velocity = { V_END, 0 } })
  return sim, nbar
end

-- The cells of the bar's two middle rows between the grips' inner faces
-- (two cells in from each) that hold no particle (`empty`) and that no
-- particle's domain reaches (`unreached`: the bounding box of the
-- parallelogram spanned by the columns of F times half the particle's
-- initial side, the domain CPDI and splitting track, overlaps the cell;
-- with `domain` = "corners", a CPDI2 run, the box of the quadrilateral it
-- tracks; with "axes", cpGIMP's box, half-widths F_xx and F_yy times that
-- half side); the bar's length and mean axial stress, and its particles'
-- smallest and largest axial stretch F_xx away from the grips (|x| < 1.2 m).
function B.inspect(sim, domain)
  local CELL = B.CELL
  local n = sim:particle_count()
  local F, vol = sim:field("deformation_gradient"), sim:field("volume")
  local q = domain == "corners" and sim:field("cpdi2_corners")
  local cells, boxes, sxx, v = {}, {}, 0, 0
  local grip_lo, grip_hi, lo, hi = -math.huge, math.huge, math.huge, -math.huge
  local fmin, fmax = math.huge, -math.huge
  for i = 1, n do
    local p = sim:particle(i)
    if p.material == 2 then
      if p.x[1] < 0 then grip_lo = math.max(grip_lo, p.x[1]) else grip_hi = math.min(grip_hi, p.x[1]) end
    else
      cells[math.floor((p.x[1] + 2) / CELL) * 1000 + math.floor(p.x[2] / CELL)] = true
      sxx, v = sxx + p.stress[1] * p.volume, v + p.volume
      lo, hi = math.min(lo, p.x[1]), math.max(hi, p.x[1])
      local k = 9 * (i - 1)
      local fxx, fxy, fyx, fyy = F[k + 1], F[k + 2], F[k + 4], F[k + 5]
      local r = 0.5 * math.sqrt(vol[i] / (fxx * fyy - fxy * fyx))
      local ex, ey = r * (math.abs(fxx) + math.abs(fxy)), r * (math.abs(fyx) + math.abs(fyy))
      if domain == "axes" then ex, ey = r * fxx, r * fyy end
      local box = { p.x[1] - ex, p.x[1] + ex, p.x[2] - ey, p.x[2] + ey }
      if q then
        local c = 8 * (i - 1)
        box = { math.huge, -math.huge, math.huge, -math.huge }
        for k = 0, 3 do
          local cx, cy = p.x[1] + q[c + 2 * k + 1], p.x[2] + q[c + 2 * k + 2]
          box = { math.min(box[1], cx), math.max(box[2], cx), math.min(box[3], cy), math.max(box[4], cy) }
        end
      end
      boxes[#boxes + 1] = box
      if math.abs(p.x[1]) < 1.2 then fmin, fmax = math.min(fmin, fxx), math.max(fmax, fxx) end
    end
  end
  local empty, unreached = 0, 0
  local first, last = math.floor((grip_lo + 2) / CELL) + 2, math.floor((grip_hi + 2) / CELL) - 2
  for cx = first, last do
    for _, cy in ipairs{ 4, 5 } do -- y in [0.1, 0.15]: the middle of the bar (0.075 to 0.175 at the start)
      if not cells[cx * 1000 + cy] then empty = empty + 1 end
      local x0, y0, reached = cx * CELL - 2, cy * CELL, false
      for _, b in ipairs(boxes) do
        if b[1] < x0 + CELL and b[2] > x0 and b[3] < y0 + CELL and b[4] > y0 then reached = true break end
      end
      if not reached then unreached = unreached + 1 end
    end
  end
  return { empty = empty, unreached = unreached, length = grip_hi - grip_lo, stress = sxx / v, particles = n,
           span = hi - lo, fxx_min = fmin, fxx_max = fmax }
end

--- Builds the bar with `shape` and `scheme`, pulls it to 3 L0 and inspects
-- it (`domain` as in B.inspect); checks through T (testlib.lua) that the
-- mass is kept to 1e-12 and the bar is 3 L0 long between the grips within
-- 2 %, and returns what B.inspect returns.
function B.run(T, shape, scheme, domain)
  local sim = B.build{ shape = shape, scheme = scheme, split = false, name = shape .. "_" .. scheme }
  local mass0 = sim:diagnostics().mass
  sim:run{ time = B.T_END }
  local r = B.inspect(sim, domain)
  print(string.format("tension bar %-6s %-4s: %.3f m long, %d cells without a particle, %d unreached by a " ..
                      "domain, F_xx in [%.3f, %.3f] (exact 3)", shape, scheme, r.length, r.empty, r.unreached,
                      r.fxx_min, r.fxx_max))
  T.close(sim:diagnostics().mass, mass0, 1e-12, shape .. " " .. scheme .. ": mass")
  T.close(r.length, 3 * B.L0, 0.02, shape .. " " .. scheme .. ": length between the grips")
  sim:free()
  return r
end

return B

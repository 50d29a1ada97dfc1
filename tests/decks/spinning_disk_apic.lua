-- Rotating disk of Jiang, Schroeder & Teran (the APIC paper, JCP 2017, §6.1),
-- as 000 reproduces it in App. B.2 (Figs. 25, 26): PIC, FLIP and APIC spin a
-- free elastic disk; the angular momentum about the centroid (000, Eq. 56).
-- 000's settings: 0.6 m diameter, Hooke's law, USL, boundary-modified cubic
-- B-splines, l_cell = 0.0625 and 0.03125 m, a_tau from 1e-2 to 0.2 with
-- 1.4e-5 s <= dt <= 2.8e-4 s. That range is dt = a_tau l_cell sqrt(rho/E)
-- (000, Eq. 29) with l_cell = 0.0625 m only if E / rho = 2000 m^2/s^2 (taken
-- here). Assumed (not found in the sources at hand): rho = 1000 kg/m^3, so
-- E = 2 MPa; nu = 0.3; omega = 2 pi rad/s; 2 x 2 points per cell; 4 s as
-- [18]'s PIC curve; a free grid with two cells of margin beyond the support.
-- Runs: PIC, FLIP, APIC at each cell and a_tau; L/L0 after the first step and
-- at the end, and the whole history in disk_<transfer>_<cell>_<a_tau>.csv.
-- Checks: PIC's first-step loss within 15 % of 4 h^2 / (3 R^2) (below);
-- FLIP loses at least twice as much on the coarse mesh as on the fine one
-- (000 Fig. 26); APIC keeps L to 1e-12 through the first step, and its drift
-- halves with dt (within [0.4, 0.6], on runs of 2 s or more). Reported: PIC's
-- first-step loss against 000's "almost all", the time PIC takes to lose half,
-- FLIP against the step (000 Fig. 26).
-- --set cells=..., a_tau=..., transfers=..., time=T pick a part.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local rho, E, nu, R, omega = 1000, 2e6, 0.3, 0.3, 2 * math.pi
local duration = mpm.param("time", 4.0)
local disk = mpm.material.linear_elastic{ density = rho, E = E, nu = nu }

local function spin(transfer, h, a_tau)
  local side = h * math.ceil((2 * R) / h + 8) -- the disk, the cubic support (2 cells) and a margin, each side
  local c = side / 2
  local sim = mpm.simulation{
    dim = 2, grid = { size = { side, side }, cell = h }, shape = "cubic_bspline", shape_boundary = "modified",
    scheme = { transfer = transfer, stress_update = "USL" }, dt = { a_tau = a_tau }, boundary = { all = "free" },
    thermo = 0, diagnostics = string.format("disk_%s_%s_%s.csv", transfer, h, a_tau), diagnostics_every = 50,
  }
  sim:add_particles(mpm.disk{ center = { c, c }, radius = R }, { material = disk, per_axis = 2,
                    velocity = mpm.rigid_rotation{ omega = omega, center = { c, c } } })
  local L0 = sim:diagnostics().L_centroid
  sim:run{ steps = 1 }
  local r = { first = sim:diagnostics().L_centroid / L0, dt = sim:dt() }
  sim:hook{ every_steps = 1, fn = function(s)
    if not r.half and s:diagnostics().L_centroid < L0 / 2 then r.half = s:time() end
  end }
  sim:run{ end_time = duration }
  r.last = sim:diagnostics().L_centroid / L0
  sim:free()
  return r
end

local cells = T.list(mpm.param("cells", "0.0625,0.03125"))
local steps = T.list(mpm.param("a_tau", "0.2,0.1,0.05,0.01"))
local transfers = T.list(mpm.param("transfers", "PIC,FLIP,APIC"))
local r, id = {}, "spinning_disk_apic."
for _, h in ipairs(cells) do
  for _, a_tau in ipairs(steps) do
    for _, transfer in ipairs(transfers) do
      local key = transfer .. "." .. h .. "." .. a_tau
      local x = spin(transfer, tonumber(h), tonumber(a_tau))
      r[key] = x
      print(string.format("rotating disk %-4s cell %-7s a_tau %-5s dt %.3g s: 1 - L/L0 = %.3e after one step; " ..
                          "L/L0 = %.6f at %g s; below 1/2 from %s", transfer, h, a_tau, x.dt, 1 - x.first, x.last,
                          duration, x.half and string.format("%.4g s", x.half) or "never"))
      T.expect{ id = id .. key .. ".L", value = x.last, detail = true,
                what = string.format("%s, l_cell %s, a_tau %s: L/L0 at %g s", transfer, h, a_tau, duration) }
    end
  end
end

-- PIC keeps, of a rigid rotation, what the grid's nodal velocities carry:
-- G2P drops each particle's affine part, whose angular momentum is
-- m omega tr(D_p), D_p = h^2/3 I for cubic B-splines (the inertia-like
-- tensor of APIC). Over the disk, whose mean r^2 is R^2/2,
-- the first step thus loses 4 h^2 / (3 R^2) of L (the nodes at the rim,
-- with fewer particles, make it a little less). Whatever dt.
for _, h in ipairs(cells) do
  local x = r["PIC." .. h .. "." .. steps[1]]
  if x then
    local hh = tonumber(h)
    T.expect{ id = id .. "PIC_first." .. h, unit = "%", value = 100 * (1 - x.first),
              reference = 100 * 4 * hh * hh / (3 * R * R), rtol = 0.15,
              what = string.format("PIC, l_cell %s: L lost in the first step (estimate 4 h^2 / (3 R^2))", h) }
    T.expect{ id = id .. "PIC_almost_all." .. h, unit = "%", value = 100 * (1 - x.first), min = 90, asserted = false,
              what = string.format("PIC, l_cell %s: L lost in the first step (000: \"almost all\")", h) }
    T.expect{ id = id .. "PIC_half." .. h, unit = "s", value = x.half or duration, asserted = false,
              what = string.format("PIC, l_cell %s, a_tau %s: time at which L falls below L0/2 ([18]: slowly, over about 4 s)",
                                   h, steps[1]) }
  end
end

-- FLIP: the coarser mesh loses more (000 Fig. 26: "significant impact")
local coarse, fine = cells[1], cells[2]
for _, a_tau in ipairs(steps) do
  local a, b = r["FLIP." .. coarse .. "." .. a_tau], r["FLIP." .. fine .. "." .. a_tau]
  if a and b then
    T.expect{ id = id .. "FLIP_mesh." .. a_tau, value = (1 - a.last) / (1 - b.last), min = 2,
              what = string.format("FLIP, a_tau %s: L lost on l_cell %s over L lost on %s (000 Fig. 26: the coarse mesh loses much more)",
                                   a_tau, coarse, fine) }
  end
end
-- FLIP: the larger step keeps more (000 Fig. 26: "higher time steps actually
-- promote the conservation", the variations small). Reported, not held:
-- moraine's FLIP keeps more with the larger step over the first tenths of a
-- second only; over 4 s the smaller step keeps more (the loss is a time
-- discretisation error, not one per transfer as PIC's).
local big, small = steps[1], steps[#steps]
for _, h in ipairs(cells) do
  local a, b = r["FLIP." .. h .. "." .. big], r["FLIP." .. h .. "." .. small]
  if a and b and big ~= small then
    T.expect{ id = id .. "FLIP_dt." .. h, value = a.last, min = b.last, asserted = false,
              what = string.format("FLIP, l_cell %s: L/L0 at a_tau %s, at least that at a_tau %s (%.6f) (000 Fig. 26)",
                                   h, big, small, b.last) }
  end
end
-- APIC: the transfers conserve L (Jiang et al.); what is left is the first
-- order error of the explicit position update, which halves with dt
for _, h in ipairs(cells) do
  local a = r["APIC." .. h .. "." .. steps[1]]
  if a then
    T.expect{ id = id .. "APIC_first." .. h, value = math.abs(1 - a.first), max = 1e-12,
              what = string.format("APIC, l_cell %s: |1 - L/L0| after the first step (transfers conserve L)", h) }
  end
  for k = 1, #steps - 1 do
    local x, y = r["APIC." .. h .. "." .. steps[k]], r["APIC." .. h .. "." .. steps[k + 1]]
    if x and y and math.abs(tonumber(steps[k + 1]) * 2 - tonumber(steps[k])) < 1e-12 then
      T.expect{ id = id .. "APIC_order." .. h .. "." .. steps[k + 1], value = math.abs(1 - y.last) / math.abs(1 - x.last),
                min = 0.4, max = 0.6, asserted = duration >= 2,
                what = string.format("APIC, l_cell %s: |1 - L/L0| at a_tau %s over that at %s (first order: 0.5)",
                                     h, steps[k + 1], steps[k]) }
    end
  end
end
T.done("spinning_disk_apic")

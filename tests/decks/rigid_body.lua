-- Rigid bodies (sim:add_wall with a density or a mass) against closed forms.
--
-- free      2D bodies clear of the material, gravity g = 9.81, 0.3 s at
--           dt = 1 ms: the mass and inertia from the geometry (a box
--           0.2 x 0.2 m at 2000 kg/m^3: m = 80 kg/m, I = m (w^2 + h^2) / 12;
--           a disk r = 0.1 m at 500 kg/m^3: I = m r^2 / 2; a right triangle
--           of legs a = 0.3, b = 0.4 m given m = 12 kg/m: I = m (a^2 + b^2)
--           / 18 about its centroid), to 1e-12. Each falls at g: v_y = -g t
--           to 1e-12, the centre y0 - g dt^2 n (n + 1) / 2 (semi-implicit
--           Euler) to 1e-12 m; the box keeps its initial v_x and turns as
--           omega = M t / I under its external moment M; the disk, fixed in
--           x and rz, does not move along x nor turn under an external
--           force along x and a moment; the bodies' kinetic energy equals
--           the work of gravity and loads on them plus their initial one.
--           A 3D box spinning about a principal axis falls at g and keeps
--           its spin; fixed in y it keeps its velocity along y. A box
--           tumbling about no principal axis keeps its angular momentum
--           I omega (I turned with it) to 1e-12 and its kinetic energy to
--           1e-3. A mesh body (an STL box 0.2 x 0.1 x 0.3 m turned by 30
--           degrees about z) has the mass, centre and inertia tensor
--           R diag(I) R^T of the box to 1e-12.
-- momentum  an elastic block (0.4 m, E = 1 MPa, rho = 1000) in the air hit
--           by a disk body (r = 0.1 m, 1500 kg/m^3, v = (2, 0.3) m/s,
--           omega = 5 rad/s), 0.2 s, both under gravity and clear of the
--           faces: the momentum of block + disk changes by (m + M) g t
--           only, to 1e-9 of the impulse exchanged (FLIP and APIC); under
--           FLIP |W_MPM| stays below 2 % of the energy exchanged.
-- restart   the collision run 0.1 s straight and 0.05 + save/load + 0.05 s:
--           particles, the body's velocity, spin, place and the work on it
--           agree bit for bit.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local g = 9.81

local function simulation(o)
  return mpm.simulation{ dim = o.dim or 2, grid = { size = o.size or { 2.0, 2.0 }, cell = o.cell or 0.05 },
                         shape = "quadratic_bspline", scheme = o.scheme or "APIC",
                         gravity = o.dim == 3 and { 0, 0, -g } or { 0, -g }, boundary = { all = "slip" },
                         dt = o.dt or { a_tau = 0.3 }, diagnostics = false, thermo = 0, progress = false }
end

-- ---- free bodies -----------------------------------------------------------------------
local function free_2d()
  local sim = simulation{ dt = 1e-3 }
  local Mz = 3.0
  sim:add_wall{ name = "box", shape = "box", min = { 0.2, 1.5 }, max = { 0.4, 1.7 }, density = 2000,
                velocity = { 0.1, 0 }, external_moment = Mz }
  sim:add_wall{ name = "disk", shape = "cylinder", center = { 1.0, 1.6 }, radius = 0.1, density = 500,
                fix = { "x", "rz" }, external_force = { 100, 0 }, external_moment = 1 }
  sim:add_wall{ name = "tri", shape = "polygon", vertices = { { 1.4, 1.5 }, { 1.7, 1.5 }, { 1.4, 1.9 } }, mass = 12 }
  -- material far below, so the run has particles; the bodies never reach it
  sim:add_particles(mpm.box{ min = { 0.5, 0.0 }, max = { 1.5, 0.2 } },
                    { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }, per_cell = 4 })
  local box, disk, tri = sim:wall("box"), sim:wall("disk"), sim:wall("tri")
  T.close(box.mass, 80, 1e-12, "box mass")
  T.close(box.inertia, 80 * (0.04 + 0.04) / 12, 1e-12, "box inertia")
  T.close(disk.mass, 500 * math.pi * 0.01, 1e-12, "disk mass")
  T.close(disk.inertia, disk.mass * 0.01 / 2, 1e-12, "disk inertia")
  T.close(tri.inertia, 12 * (0.09 + 0.16) / 18, 1e-12, "triangle inertia")
  T.close(tri.pivot[1], 1.5, 1e-12, "triangle centroid x")
  T.close(tri.pivot[2], 1.5 + 0.4 / 3, 1e-12, "triangle centroid y")
  local y0 = { box = box.pivot[2], disk = disk.pivot[2], tri = tri.pivot[2] }
  local x0 = disk.pivot[1]
  local e0 = sim:diagnostics().E_bodies
  local n = 300
  sim:run{ steps = n }
  local t, dt = sim:time(), 1e-3
  for _, name in ipairs{ "box", "disk", "tri" } do
    local w = sim:wall(name)
    T.close(w.velocity[2], -g * t, 1e-12, name .. ": v_y against -g t")
    T.close(w.pivot[2], y0[name] - g * dt * dt * n * (n + 1) / 2, 0, name .. ": height", 1e-12)
  end
  box, disk = sim:wall("box"), sim:wall("disk")
  T.check(box.velocity[1] == 0.1, "box: v_x %.17g changed", box.velocity[1])
  T.close(box.omega, Mz * t / box.inertia, 1e-12, "box: omega = M t / I")
  T.check(disk.velocity[1] == 0 and disk.pivot[1] == x0 and disk.omega == 0,
          "disk fixed in x and rz moved: v_x %g, x %g (from %g), omega %g", disk.velocity[1], disk.pivot[1], x0,
          disk.omega)
  local d = sim:diagnostics()
  T.close(d.E_bodies, e0 + d.W_bodies, 1e-12, "E_bodies = E_bodies(0) + W_bodies")
end

local function free_3d()
  local sim = simulation{ dim = 3, size = { 1, 1, 1 }, cell = 0.1, dt = 1e-3 }
  sim:add_wall{ name = "box", shape = "box", min = { 0.3, 0.3, 0.6 }, max = { 0.5, 0.4, 0.9 }, density = 1000,
                omega = { 0, 0, 4 }, velocity = { 0, 0.2, 0 }, fix = { "y" } }
  sim:add_wall{ name = "tumbler", shape = "box", min = { 0.6, 0.3, 0.6 }, max = { 0.9, 0.45, 0.65 }, density = 1000,
                omega = { 1, 2, 3 } }
  sim:add_particles(mpm.box{ min = { 0, 0, 0 }, max = { 1, 1, 0.1 } },
                    { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }, per_cell = 8 })
  -- the tumbler's angular momentum I omega, I in its current placement
  local function spin(w)
    local I, o = w.inertia, w.omega
    return { I[1] * o[1] + I[2] * o[2] + I[3] * o[3], I[4] * o[1] + I[5] * o[2] + I[6] * o[3],
             I[7] * o[1] + I[8] * o[2] + I[9] * o[3] }
  end
  local L0, e0 = spin(sim:wall("tumbler")), sim:wall("tumbler").kinetic
  local w0 = sim:wall("box")
  T.close(w0.mass, 1000 * 0.2 * 0.1 * 0.3, 1e-12, "3D box mass")
  T.close(w0.inertia[9], w0.mass * (0.04 + 0.01) / 12, 1e-12, "3D box I_zz")
  sim:run{ steps = 200 }
  local w = sim:wall("box")
  T.close(w.velocity[3], -g * sim:time(), 1e-12, "3D box: v_z against -g t")
  T.check(w.velocity[2] == 0.2 and w.velocity[1] == 0, "3D box: v_x, v_y changed")
  T.close(w.pivot[2], w0.pivot[2] + 0.2 * sim:time(), 1e-12, "3D box: y moves with its fixed velocity")
  T.close(w.omega[3], 4, 1e-12, "3D box: spin about a principal axis")
  -- torque-free tumbling about no principal axis: the angular momentum is
  -- what the update conserves; the energy drifts at first order in dt
  local tb, L = sim:wall("tumbler"), spin(sim:wall("tumbler"))
  local norm = math.sqrt(L0[1] ^ 2 + L0[2] ^ 2 + L0[3] ^ 2)
  local dL = math.sqrt((L[1] - L0[1]) ^ 2 + (L[2] - L0[2]) ^ 2 + (L[3] - L0[3]) ^ 2) / norm
  T.expect{ id = "rigid_body.tumbler_L", what = "3D tumbler: |L - L0| / |L0| after 0.2 s at dt = 1 ms", value = dL,
            max = 1e-12 }
  T.expect{ id = "rigid_body.tumbler_E", what = "3D tumbler: |E - E0 - W_bodies| / E0 after 0.2 s at dt = 1 ms",
            value = math.abs(tb.kinetic - e0 - tb.body_work) / e0, max = 1e-3 }
end

-- a box turned about z as a closed mesh in an ASCII STL file: its mass,
-- centre of mass and full inertia tensor against the box's closed form
local function mesh_body()
  local a, c0, h = math.rad(30), { 0.5, 0.5, 0.5 }, { 0.1, 0.05, 0.15 }
  local ca, sa = math.cos(a), math.sin(a)
  local function corner(i) -- bits of i: x, y, z high
    local q = { (i & 1 > 0) and h[1] or -h[1], (i & 2 > 0) and h[2] or -h[2], (i & 4 > 0) and h[3] or -h[3] }
    return { c0[1] + ca * q[1] - sa * q[2], c0[2] + sa * q[1] + ca * q[2], c0[3] + q[3] }
  end
  local faces = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 } }
  local path = mpm.outdir .. "/turned_box.stl"
  local f = assert(io.open(path, "w"))
  f:write("solid turned_box\n")
  for _, q in ipairs(faces) do
    for _, t in ipairs{ { q[1], q[2], q[3] }, { q[1], q[3], q[4] } } do
      f:write("facet normal 0 0 0\nouter loop\n")
      for _, k in ipairs(t) do
        local p = corner(k)
        f:write(string.format("vertex %.17g %.17g %.17g\n", p[1], p[2], p[3]))
      end
      f:write("endloop\nendfacet\n")
    end
  end
  f:write("endsolid turned_box\n")
  f:close()
  local sim = simulation{ dim = 3, size = { 1, 1, 1 }, cell = 0.1, dt = 1e-3 }
  sim:add_wall{ name = "mesh", shape = "mesh", file = path, density = 1000 }
  local w = sim:wall("mesh")
  local m = 1000 * 8 * h[1] * h[2] * h[3]
  T.close(w.mass, m, 1e-12, "mesh body: mass")
  for d = 1, 3 do T.check(math.abs(w.pivot[d] - c0[d]) <= 1e-12, "mesh body: centre %d at %.17g", d, w.pivot[d]) end
  local I0 = { m * (h[2] ^ 2 + h[3] ^ 2) / 3, m * (h[1] ^ 2 + h[3] ^ 2) / 3, m * (h[1] ^ 2 + h[2] ^ 2) / 3 }
  local R = { { ca, -sa, 0 }, { sa, ca, 0 }, { 0, 0, 1 } }
  for i = 1, 3 do
    for j = 1, 3 do
      local want = 0
      for k = 1, 3 do want = want + R[i][k] * I0[k] * R[j][k] end
      T.check(math.abs(w.inertia[3 * (i - 1) + j] - want) <= 1e-12 * I0[3],
              "mesh body: inertia[%d][%d] = %.17g, the turned box's %.17g", i, j, w.inertia[3 * (i - 1) + j], want)
    end
  end
end

-- ---- momentum and restart --------------------------------------------------------------
local function collision(scheme)
  local sim = simulation{ cell = 0.025, scheme = scheme }
  sim:add_particles(mpm.box{ min = { 0.8, 1.2 }, max = { 1.2, 1.6 } },
                    { material = mpm.material.linear_elastic{ density = 1000, E = 1e6, nu = 0.3 }, per_cell = 4 })
  sim:add_wall{ name = "disk", shape = "cylinder", center = { 0.6, 1.45 }, radius = 0.1, density = 1500,
                velocity = { 2.0, 0.3 }, omega = 5 }
  return sim
end

local function momentum(scheme)
  local sim = collision(scheme)
  local M = sim:wall("disk").mass
  local function total()
    local d, w = sim:diagnostics(), sim:wall("disk")
    return d.momentum_x + M * w.velocity[1], d.momentum_y + M * w.velocity[2], d.mass
  end
  local px0, py0, m = total()
  local e0 = sim:diagnostics().E_bodies
  sim:run{ time = 0.2 }
  local px, py = total()
  local w, d = sim:wall("disk"), sim:diagnostics()
  local J = math.sqrt(w.impulse[1] ^ 2 + w.impulse[2] ^ 2)
  T.check(J > 50, "%s: the disk hardly hit the block (impulse %g N s/m)", scheme, J)
  local err = math.max(math.abs(px - px0), math.abs(py - py0 + (m + M) * g * sim:time())) / J
  T.expect{ id = "rigid_body.momentum." .. scheme, what = scheme .. ": |P - P0 - (m + M) g t| / impulse exchanged",
            value = err, max = 1e-9 }
  local exchanged = e0 + d.W_bodies - d.E_bodies -- what the disk gave the block
  T.expect{ id = "rigid_body.energy." .. scheme, what = scheme .. ": |W_MPM| / energy the disk gave the block",
            value = math.abs(d.W_MPM) / exchanged, max = 0.02, asserted = scheme == "FLIP" }
end

local function restart()
  local straight = collision("APIC")
  straight:run{ steps = 400 }
  local first = collision("APIC")
  first:run{ steps = 200 }
  local again = mpm.load(first:save("rigid_body_restart.h5"))
  again:run{ steps = 200 }
  for i = 1, straight:particle_count() do
    local a, b = straight:particle(i), again:particle(i)
    for k = 1, 2 do T.check(a.x[k] == b.x[k] and a.v[k] == b.v[k], "particle %d differs after the restart", i) end
  end
  local a, b = straight:wall("disk"), again:wall("disk")
  for k = 1, 2 do
    T.check(a.velocity[k] == b.velocity[k] and a.pivot[k] == b.pivot[k], "the disk differs after the restart")
  end
  for k = 1, 9 do T.check(a.rotation[k] == b.rotation[k], "the disk's rotation differs after the restart") end
  T.check(a.omega == b.omega and a.body_work == b.body_work and a.work == b.work,
          "the disk's spin or work differs after the restart")
  local da, db = straight:diagnostics(), again:diagnostics()
  T.check(da.E_bodies == db.E_bodies and da.W_bodies == db.W_bodies and da.W_MPM == db.W_MPM,
          "E_bodies, W_bodies or W_MPM differ after the restart")
end

free_2d()
free_3d()
mesh_body()
momentum("FLIP")
momentum("APIC")
restart()
T.done("rigid_body")

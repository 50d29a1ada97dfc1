-- Steady dense granular flow down a rough inclined plane with the mu(I)
-- rheology (Jop, Forterre and Pouliquen 2006; GDR MiDi 2004): a layer of
-- depth H on a no-slip base, periodic along the slope, gravity tilted by
-- theta between the two friction angles (atan mu_s < theta < atan mu_2).
-- Everywhere tau / p = tan(theta), so I is uniform,
--   I_theta = I0 (tan theta - mu_s) / (mu_2 - tan theta),
-- and with p = phi rho_s g cos(theta) (H - z), phi = density / rho_s, the
-- shear rate gamma_dot = I_theta sqrt(p / rho_s) / d integrates to the
-- Bagnold profile
--   u(z) = (2/3) (I_theta / d) sqrt(phi g cos theta) (H^{3/2} - (H - z)^{3/2}).
-- Glass beads (d = 0.5 mm, rho_s = 2450, phi = 0.6), H = 20 grains, theta =
-- 25 deg: I_theta = 0.133, surface speed 0.42 m/s. Elastic moduli E = 2e5 Pa
-- (volumetric strain at the base 1.6e-3). Quadratic B-splines with the WLS
-- correction at the base, APIC, USF. The layer starts at rest and runs to
-- t_end; the profile of the particle velocities is compared with u(z):
-- e_max = max_p |u_p - u(z_p)| / u(H), and the surface speed drift over the
-- last tenth of the run says whether the flow is steady.
-- The flow is steady by t = 4 s (the surface speed changes by 0.1 % over
-- the last 0.4 s). The error is first order in the cell size, from the
-- base (the no-slip velocity is reached about 0.4 cell above it) and from
-- the free surface: 8 cells across H give e_max 10.6 % (surface speed
-- +10 %), 16 cells 5.3 % (+5 %).
-- Quick (the default: 8 cells, t_end = 4 s, ~5 s of CPU): asserts e_max
-- < 12 % and the drift < 1 %. Full (--set full=true: 16 cells, ~20 s of
-- CPU): e_max < 6 %. --set profile=true prints the particle profile.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local deg = math.pi / 180
local d, rho_s, phi, g = 0.5e-3, 2450, 0.6, 9.81
local mu_s, mu_2, I0 = math.tan(20.9 * deg), math.tan(32.76 * deg), 0.279
local theta = mpm.param("theta", 25) * deg
local H = 20 * d
local full = mpm.param("full", false)
local N = mpm.param("cells", full and 16 or 8)
local t_end = mpm.param("t_end", 4.0)
local tol = mpm.param("tolerance", full and 0.06 or 0.12)
local h = H / N

local beads = mpm.material.mu_i{ density = phi * rho_s, E = 2e5, nu = 0.3, mu_s = mu_s, mu_2 = mu_2, I0 = I0,
                                 d = d, rho_s = rho_s }
local I_theta = I0 * (math.tan(theta) - mu_s) / (mu_2 - math.tan(theta))
local A = 2 / 3 * I_theta / d * math.sqrt(phi * g * math.cos(theta))
local function u(z) return A * (H ^ 1.5 - math.max(H - z, 0) ^ 1.5) end

local sim <close> = mpm.simulation{ dim = 2, grid = { size = { 4 * h, 1.5 * H }, cell = h },
  shape = "quadratic_bspline", shape_boundary = "wls", scheme = { transfer = "APIC", stress_update = "USF" },
  gravity = { g * math.sin(theta), -g * math.cos(theta) },
  boundary = { left = "periodic", right = "periodic", bottom = "fixed", top = "free" },
  dt = { cfl = 0.5 }, thermo = 0, diagnostics = false }
-- from the hydrostatic stress (K0 = 1) of the tilted weight: no settling wave
sim:add_particles(mpm.box{ min = { 0, 0 }, max = { 4 * h, H } }, { material = beads, per_axis = 2,
  stress = mpm.lithostatic{ density = phi * rho_s, top = H, g = g * math.cos(theta), K0 = 1 } })
local np = sim:particle_count()

local function surface_speed()
  local v, nc = sim:field("velocity")
  local top = 0
  for i = 1, np do
    if sim:particle(i).x[2] > H - h / 2 then top = math.max(top, v[nc * (i - 1) + 1]) end
  end
  return top
end
sim:run{ time = 0.9 * t_end }
local u_before = surface_speed()
sim:run{ time = t_end - sim:time() }
local u_after = surface_speed()

local v, nc = sim:field("velocity")
if mpm.param("profile", false) then
  local st = sim:field("stress")
  for i = 1, np do
    local x = sim:particle(i).x
    if x[1] < h / 2 then
      print(string.format("z/H %.3f u %.4f bagnold %.4f  sxy %.2f syy %.2f p_hydro %.2f", x[2] / H, v[nc * (i - 1) + 1], u(x[2]),
        st[6 * (i - 1) + 4], st[6 * (i - 1) + 2], phi * rho_s * g * math.cos(theta) * (H - x[2])))
    end
  end
end
local emax, worst_z = 0, 0
for i = 1, np do
  local z = sim:particle(i).x[2]
  local e = math.abs(v[nc * (i - 1) + 1] - u(z)) / u(H)
  if e > emax then emax, worst_z = e, z end
end
print(string.format("inclined plane: theta = %.1f deg, I_theta = %.4f, u(H) = %.4f m/s; N = %d, t = %.2f s, %d steps",
                    theta / deg, I_theta, u(H), N, sim:time(), sim:step()))
print(string.format("inclined plane: surface speed %.4f m/s (%.2f %% of u(H)), drift over the last tenth %.2f %%, " ..
                    "e_max %.2f %% at z/H = %.2f", u_after, 100 * u_after / u(H), 100 * (u_after / u_before - 1),
                    100 * emax, worst_z / H))
T.expect{ id = "inclined_plane.drift", what = "surface speed change over the last tenth of the run", unit = "%",
          value = 100 * math.abs(u_after / u_before - 1), max = 1 }
T.expect{ id = "inclined_plane.emax", what = string.format("Bagnold profile e_max, %d cells across H", N), unit = "%",
          value = 100 * emax, max = 100 * tol }
T.done("inclined_plane")

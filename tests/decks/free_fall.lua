-- Free fall (000 §4.1: every strategy is exact in free fall). For every
-- transfer, stress-update scheme and shape function, in 2D and 3D, the centre
-- of mass follows the scheme's exact discrete trajectory: v_n = g t_n and
-- x_n = x_0 + g dt^2 n (n + 1) / 2 (positions use the updated velocity), to
-- 1e-9 relative. That trajectory differs from the continuous g t^2 / 2 by
-- g t dt / 2 (first order in dt), which the test also reports.
local T = dofile(mpm.deck_dir .. "/testlib.lua")
local mat = mpm.material.linear_elastic{ density = 1500, E = 5e6, nu = 0.25 }
local g, dt, steps = 9.81, 2e-4, 400

local worst_continuous, worst_v, worst_x, cases = 0, 0, 0, 0
for _, dim in ipairs{ 2, 3 } do
  for _, shape in ipairs{ "linear", "quadratic_bspline" } do
    for _, transfer in ipairs{ "PIC", "FLIP", "FLIP0.7", "NFLIP", "NFLIP0.9" } do
      for _, su in ipairs{ "USF", "USL", "MUSL" } do
        local size = dim == 2 and { 1, 2 } or { 1, 1, 2 }
        local grav = dim == 2 and { 0, -g } or { 0, 0, -g }
        local sim = mpm.simulation{ dim = dim, grid = { size = size, cell = 0.1 }, shape = shape, gravity = grav,
                                    scheme = { transfer = transfer, stress_update = su }, dt = { fixed = dt },
                                    boundary = { all = "free" }, thermo = 0, diagnostics = false }
        local lo = dim == 2 and { 0.3, 1.5 } or { 0.3, 0.3, 1.5 }
        local hi = dim == 2 and { 0.7, 1.9 } or { 0.7, 0.7, 1.9 }
        sim:add_particles(mpm.box{ min = lo, max = hi }, { material = mat, per_axis = 2 })
        local z0 = sim:diagnostics().center_of_mass[dim]
        sim:run{ steps = steps }
        local d = sim:diagnostics()
        local t = sim:time()
        local label = string.format("%dD %s %s %s", dim, shape, transfer, su)
        worst_v = math.max(worst_v, T.close(d.com_velocity[dim], -g * t, 1e-9, label .. " velocity"))
        local drop = z0 - d.center_of_mass[dim]
        worst_x = math.max(worst_x, T.close(drop, g * dt * dt * steps * (steps + 1) / 2, 1e-9, label .. " position"))
        cases = cases + 1
        worst_continuous = math.max(worst_continuous, math.abs(drop - g * t * t / 2) / (g * t * t / 2))
        for k = 1, dim - 1 do T.close(d.com_velocity[k], 0, 0, label .. " lateral velocity", 1e-12) end
        sim:free()
      end
    end
  end
end
print(string.format("free fall: largest departure from g t^2/2 = %.3g (dt / t = %.3g)", worst_continuous,
                    dt / (dt * steps)))
T.expect{ id = "free_fall.velocity", what = string.format("largest relative error of v_cm against g t (%d set-ups)", cases),
           value = worst_v, max = 1e-9 }
T.expect{ id = "free_fall.position", what = "largest relative error of the drop against g dt^2 n (n + 1) / 2",
           value = worst_x, max = 1e-9 }
T.expect{ id = "free_fall.continuous", what = "largest departure of the drop from g t^2 / 2 (first order in dt)",
           value = worst_continuous, asserted = false }
T.done("free_fall")

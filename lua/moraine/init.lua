-- moraine: the pure-Lua part of the `moraine` module.
--
-- The C engine creates the module table; this file adds the helpers that are
-- easiest to write in Lua. It returns a function that receives the module.
return function(mpm)
  mpm.dt = mpm.dt or {}

  --- mpm.dt.fixed(dt): a constant time step (s).
  function mpm.dt.fixed(dt, bounds)
    local t = { fixed = dt }
    for k, v in pairs(bounds or {}) do t[k] = v end
    return t
  end

  --- mpm.dt.a_tau(a_tau): dt = a_tau * l_cell * sqrt(rho / E) (000, Eq. 29).
  function mpm.dt.a_tau(a_tau, bounds)
    local t = { a_tau = a_tau }
    for k, v in pairs(bounds or {}) do t[k] = v end
    return t
  end

  --- mpm.rigid_rotation{omega = w, center = {cx, cy[, cz]}, axis = {ax, ay, az}, velocity = {...}}
  -- A velocity field for add_particles{velocity = ...}: v = V + omega x (x - c).
  -- In 2D omega is the rate about z (rad/s); in 3D it is the rate about `axis`
  -- (normalised here; default z).
  function mpm.rigid_rotation(t)
    local w = assert(t.omega, "rigid_rotation: omega is required")
    local c = t.center or { 0, 0, 0 }
    local ax = t.axis or { 0, 0, 1 }
    local n = math.sqrt(ax[1] ^ 2 + ax[2] ^ 2 + ax[3] ^ 2)
    local wx, wy, wz = w * ax[1] / n, w * ax[2] / n, w * ax[3] / n
    local V = t.velocity or { 0, 0, 0 }
    return function(x, y, z)
      local rx, ry, rz = x - c[1], y - c[2], z - (c[3] or 0)
      return { (V[1] or 0) + wy * rz - wz * ry,
               (V[2] or 0) + wz * rx - wx * rz,
               (V[3] or 0) + wx * ry - wy * rx }
    end
  end

  --- mpm.lithostatic{density = rho, g = 9.81, top = H, K0 = nu/(1-nu), dim = 2}
  -- An initial stress field for add_particles{stress = ...}: the vertical
  -- stress -rho g (top - height) and horizontal K0 times it (tension positive).
  -- Height is y in 2D and z in 3D.
  function mpm.lithostatic(t)
    local rho, g, top = t.density, t.g or 9.81, t.top
    local K0, dim = t.K0 or 0.5, t.dim or 2
    assert(rho and top, "lithostatic: density and top are required")
    return function(x, y, z)
      local h = dim == 2 and y or z
      local sv = -rho * g * (top - h)
      if dim == 2 then return { K0 * sv, sv, K0 * sv, 0, 0, 0 } end
      return { K0 * sv, K0 * sv, sv, 0, 0, 0 }
    end
  end
end

-- The forms of a particle snapshot (output{ format, compress, float32 }) and
-- the HDF5 series' attributes on a granular column collapse (000 §5, through
-- moraine.collapse) cut short at t = 0.3 s, mid-collapse; the files are read
-- back by tests/python/check_vtk_forms.py with VTK's own readers and xarray.
--
--   forms/<form>_000000.*   the same state in each form below (sim:write_vtk)
--   zf/, h5/                four snapshots each, every 10 steps: zlib + Float32
--                           .vtp in a .pvd, and .vtkhdf in a .vtkhdf.series
--   diagnostics.h5          the settling's series, diagnostics_2.h5 the collapse's
local collapse = require "moraine.collapse"

local r = collapse.run{ aspect_ratio = 1, collapse_time = 0.3, csv = false, keep = true, name = "collapse" }
local sim = r.collapse_sim
assert(sim:dim() == 2 and sim:particle_count() == 400, "the quick collapse: 400 particles in 2D")

local forms = {
  { "raw" },
  { "zlib", compress = 6 },
  { "zlib9", compress = 9 },
  { "f32", float32 = true },
  { "zlib_f32", compress = 6, float32 = true },
  { "ascii_f32", format = "ascii", float32 = true },
  { "vtkhdf", format = "vtkhdf" },
  { "vtkhdf_zlib_f32", format = "vtkhdf", compress = 6, float32 = true },
}
for _, f in ipairs(forms) do
  -- every key given: a key left out would keep the previous form's value
  sim:output{ vtk = "forms/" .. f[1], format = f.format or "binary", compress = f.compress or 0,
              float32 = f.float32 or false }
  sim:write_vtk()
end

sim:output{ vtk = "zf/p", every_steps = 10, format = "binary", compress = 6, float32 = true }
sim:run{ steps = 30 }
sim:output{ vtk = "h5/p", every_steps = 10, format = "vtkhdf" }
sim:run{ steps = 30 }

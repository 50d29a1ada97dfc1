#include "io/particle_fields.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/tensor.h"
#include "solver/simulation.h"
#include "transfer/probe.h"

/* the particles [first, first + count) of a fill, q counting from 0 in out */
#define FOR_PARTICLES(first, count) for (size_t q = 0, p = (first); q < (count); q++, p++)

static void copy_field(const double *src, int ncomp, size_t first, size_t count, void *out) {
  /* no particles: src may be NULL, which memcpy may not be given even for 0 bytes */
  if (count) memcpy(out, src + first * (size_t)ncomp, sizeof(double) * (size_t)ncomp * count);
}

#define FIELD_FN(name) static void name(const mrn_sim *sim, size_t first, size_t count, void *out)

FIELD_FN(f_position) { copy_field(sim->particles.x, 3, first, count, out); }
FIELD_FN(f_velocity) { copy_field(sim->particles.v, 3, first, count, out); }
FIELD_FN(f_mass) { copy_field(sim->particles.mass, 1, first, count, out); }
FIELD_FN(f_stress) { copy_field(sim->particles.stress, 6, first, count, out); }
FIELD_FN(f_strain) { copy_field(sim->particles.strain, 6, first, count, out); }
FIELD_FN(f_elastic_energy) { copy_field(sim->particles.e_elastic, 1, first, count, out); }
FIELD_FN(f_F) { mrn_particle_field_export(&sim->particles, mrn_particle_field_find("F"), first, count, out); }

FIELD_FN(f_displacement) {
  double *o = out;
  const double *x = sim->particles.x, *x0 = sim->particles.x0;
  FOR_PARTICLES(first, count) for (int d = 0; d < 3; d++) o[3 * q + d] = x[3 * p + d] - x0[3 * p + d];
}

FIELD_FN(f_volume) {
  double *o = out;
  FOR_PARTICLES(first, count) o[q] = mrn_particle_volume(&sim->particles, p);
}

FIELD_FN(f_density) {
  double *o = out;
  FOR_PARTICLES(first, count) o[q] = sim->particles.mass[p] / mrn_particle_volume(&sim->particles, p);
}

/* p = -tr(sigma) / 3, compression positive */
FIELD_FN(f_pressure) {
  double *o = out;
  FOR_PARTICLES(first, count) o[q] = -sym_trace(sim->particles.stress + 6 * p) / 3.0;
}

FIELD_FN(f_von_mises) {
  double *o = out;
  FOR_PARTICLES(first, count) o[q] = sym_von_mises(sim->particles.stress + 6 * p);
}

/* deviatoric strain norm (000, Eqs. 74-75) */
FIELD_FN(f_eps_D) {
  double *o = out, dev[6];
  FOR_PARTICLES(first, count) {
    sym_dev(sim->particles.strain + 6 * p, dev);
    o[q] = sym_norm(dev);
  }
}

/* L = sum_i V~_i (x) grad N_i at each particle (000, Eqs. 44-45), from the
 * nodal velocities of the last completed step: computed here rather than
 * stored, so runs that do not write it keep their bytes per particle */
static void particle_gradients(const mrn_sim *sim, size_t first, size_t count, double (*L)[9]) {
  const mrn_kernel_options k = mrn_sim_kernel_options(sim);
  const mrn_particles *ps = &sim->particles;
  FOR_PARTICLES(first, count) {
    mrn_probe_grid_gradient(&sim->grid, &k, sim->grid.vel_new, ps->x + 3 * p, ps->vol0[p], L[q]);
  }
}

FIELD_FN(f_velocity_gradient) { particle_gradients(sim, first, count, out); }

/* curl v from L (L[3a + b] = dv_a/dx_b); in 2D its z component alone,
 * dv/dx - du/dy */
FIELD_FN(f_vorticity) {
  enum { CHUNK = 256 }; /* particles whose L sit on the stack at once */
  double *o = out, L[CHUNK][9];
  for (size_t done = 0; done < count; done += CHUNK) {
    const size_t n = count - done < CHUNK ? count - done : CHUNK;
    particle_gradients(sim, first + done, n, L);
    for (size_t q = 0; q < n; q++) {
      const double *l = L[q];
      if (sim->dim == 2) {
        o[done + q] = l[3] - l[1];
        continue;
      }
      double *w = o + 3 * (done + q);
      w[0] = l[7] - l[5], w[1] = l[2] - l[6], w[2] = l[3] - l[1];
    }
  }
}

FIELD_FN(f_material) {
  int32_t *o = out;
  FOR_PARTICLES(first, count) o[q] = sim->particles.material[p];
}

FIELD_FN(f_id) {
  int64_t *o = out;
  FOR_PARTICLES(first, count) o[q] = sim->particles.id[p];
}

static const mrn_output_field fields[] = {
    {"velocity", 3, MRN_VTK_FLOAT64, "m/s", "particle velocity", f_velocity, 0, 0},
    {"displacement", 3, MRN_VTK_FLOAT64, "m", "position minus initial position", f_displacement, 0, 0},
    {"mass", 1, MRN_VTK_FLOAT64, "kg", "particle mass (kg/m in 2D)", f_mass, 0, 0},
    {"volume", 1, MRN_VTK_FLOAT64, "m^3", "current particle volume (m^2 in 2D)", f_volume, 0, 0},
    {"density", 1, MRN_VTK_FLOAT64, "kg/m^3", "mass / volume", f_density, 0, 0},
    {"stress", 6, MRN_VTK_FLOAT64, "Pa", "Cauchy stress xx, yy, zz, xy, yz, xz (tension positive)", f_stress, 0, 0},
    {"strain", 6, MRN_VTK_FLOAT64, "", "accumulated small strain xx, yy, zz, xy, yz, xz", f_strain, 0, 0},
    {"pressure", 1, MRN_VTK_FLOAT64, "Pa", "-tr(stress)/3, compression positive", f_pressure, 0, 0},
    {"von_mises", 1, MRN_VTK_FLOAT64, "Pa", "von Mises equivalent stress sqrt(3/2 s:s)", f_von_mises, 0, 0},
    {"eps_D", 1, MRN_VTK_FLOAT64, "", "deviatoric strain norm (000, Eq. 75)", f_eps_D, 0, 0},
    {"elastic_energy", 1, MRN_VTK_FLOAT64, "J", "elastic energy stored in the particle", f_elastic_energy, 0, 0},
    {"deformation_gradient", 9, MRN_VTK_FLOAT64, "", "F, row-major", f_F, 0, 0},
    {"material", 1, MRN_VTK_INT32, "", "material index (order of first use in the simulation)", f_material, 0, 0},
    {"id", 1, MRN_VTK_INT64, "", "particle id, stable through the run", f_id, 0, 0},
    {"velocity_gradient", 9, MRN_VTK_FLOAT64, "1/s", "grid velocity gradient L at the particle, row-major",
     f_velocity_gradient, 0, 1},
    {"vorticity", 3, MRN_VTK_FLOAT64, "1/s", "curl of the grid velocity; 2D: dv/dx - du/dy alone", f_vorticity, 1, 1},
    {"position", 3, MRN_VTK_FLOAT64, "m", "particle position (a file's points hold it already)", f_position, 0, 1},
};
enum { FIELD_COUNT = sizeof fields / sizeof fields[0] };

static const char *const names[] = {"velocity", "displacement", "mass", "volume", "density", "stress",
                                    "strain", "pressure", "von_mises", "eps_D", "elastic_energy",
                                    "deformation_gradient", "material", "id", "velocity_gradient", "vorticity",
                                    "position", NULL};

int mrn_output_field_count(void) { return FIELD_COUNT; }
const mrn_output_field *mrn_output_field_at(int i) { return &fields[i]; }
const mrn_output_field *mrn_output_field_find(const char *name) {
  for (int i = 0; i < FIELD_COUNT; i++)
    if (strcmp(fields[i].name, name) == 0) return &fields[i];
  return NULL;
}
const char *const *mrn_output_field_names(void) { return names; }

int mrn_field_lookup(const mrn_sim *sim, const char *name, mrn_field_ref *out) {
  const mrn_output_field *f = mrn_output_field_find(name);
  if (f) {
    const int ncomp = sim->dim == 2 && f->ncomp_2d ? f->ncomp_2d : f->ncomp;
    *out = (mrn_field_ref){f->name, ncomp, f->type, f, NULL};
    return 1;
  }
  const mrn_user_field *u = mrn_particles_user_field(&sim->particles, name);
  if (!u) return 0;
  *out = (mrn_field_ref){u->name, u->ncomp, MRN_VTK_FLOAT64, NULL, u};
  return 1;
}

void mrn_field_fill_range(const mrn_sim *sim, const mrn_field_ref *f, size_t first, size_t count, void *out) {
  if (f->builtin) {
    f->builtin->compute(sim, first, count, out);
    return;
  }
  const mrn_particles *ps = &sim->particles;
  double *o = out;
  FOR_PARTICLES(first, count) {
    memcpy(o + q * (size_t)f->ncomp, ps->user + p * (size_t)ps->user_stride + f->user->offset,
           sizeof(double) * f->ncomp);
  }
}

void mrn_field_fill(const mrn_sim *sim, const mrn_field_ref *f, void *out) {
  mrn_field_fill_range(sim, f, 0, sim->particles.n, out);
}

#include "io/particle_fields.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/tensor.h"
#include "solver/simulation.h"

#define FOR_PARTICLES(sim) for (size_t p = 0; p < (sim)->particles.n; p++)

static void copy_field(const double *src, int ncomp, const mrn_sim *sim, void *out) {
  /* no particles: src may be NULL, which memcpy may not be given even for 0 bytes */
  if (sim->particles.n) memcpy(out, src, sizeof(double) * ncomp * sim->particles.n);
}

static void f_velocity(const mrn_sim *sim, void *out) { copy_field(sim->particles.v, 3, sim, out); }
static void f_mass(const mrn_sim *sim, void *out) { copy_field(sim->particles.mass, 1, sim, out); }
static void f_stress(const mrn_sim *sim, void *out) { copy_field(sim->particles.stress, 6, sim, out); }
static void f_strain(const mrn_sim *sim, void *out) { copy_field(sim->particles.strain, 6, sim, out); }
static void f_F(const mrn_sim *sim, void *out) {
  mrn_particle_field_export(&sim->particles, mrn_particle_field_find("F"), 0, sim->particles.n, out);
}

static void f_displacement(const mrn_sim *sim, void *out) {
  double *o = out;
  FOR_PARTICLES(sim) for (int d = 0; d < 3; d++) o[3 * p + d] = sim->particles.x[3 * p + d] - sim->particles.x0[3 * p + d];
}

static void f_volume(const mrn_sim *sim, void *out) {
  double *o = out;
  FOR_PARTICLES(sim) o[p] = mrn_particle_volume(&sim->particles, p);
}

static void f_density(const mrn_sim *sim, void *out) {
  double *o = out;
  FOR_PARTICLES(sim) o[p] = sim->particles.mass[p] / mrn_particle_volume(&sim->particles, p);
}

/* p = -tr(sigma) / 3, compression positive */
static void f_pressure(const mrn_sim *sim, void *out) {
  double *o = out;
  FOR_PARTICLES(sim) o[p] = -sym_trace(sim->particles.stress + 6 * p) / 3.0;
}

static void f_von_mises(const mrn_sim *sim, void *out) {
  double *o = out;
  FOR_PARTICLES(sim) o[p] = sym_von_mises(sim->particles.stress + 6 * p);
}

/* deviatoric strain norm (000, Eqs. 74-75) */
static void f_eps_D(const mrn_sim *sim, void *out) {
  double *o = out, dev[6];
  FOR_PARTICLES(sim) {
    sym_dev(sim->particles.strain + 6 * p, dev);
    o[p] = sym_norm(dev);
  }
}

static void f_material(const mrn_sim *sim, void *out) {
  int32_t *o = out;
  FOR_PARTICLES(sim) o[p] = sim->particles.material[p];
}

static void f_id(const mrn_sim *sim, void *out) {
  int64_t *o = out;
  FOR_PARTICLES(sim) o[p] = sim->particles.id[p];
}

static void f_elastic_energy(const mrn_sim *sim, void *out) { copy_field(sim->particles.e_elastic, 1, sim, out); }

static const mrn_output_field fields[] = {
    {"velocity", 3, MRN_VTK_FLOAT64, "m/s", "particle velocity", f_velocity},
    {"displacement", 3, MRN_VTK_FLOAT64, "m", "position minus initial position", f_displacement},
    {"mass", 1, MRN_VTK_FLOAT64, "kg", "particle mass (kg/m in 2D)", f_mass},
    {"volume", 1, MRN_VTK_FLOAT64, "m^3", "current particle volume (m^2 in 2D)", f_volume},
    {"density", 1, MRN_VTK_FLOAT64, "kg/m^3", "mass / volume", f_density},
    {"stress", 6, MRN_VTK_FLOAT64, "Pa", "Cauchy stress xx, yy, zz, xy, yz, xz (tension positive)", f_stress},
    {"strain", 6, MRN_VTK_FLOAT64, "", "accumulated small strain xx, yy, zz, xy, yz, xz", f_strain},
    {"pressure", 1, MRN_VTK_FLOAT64, "Pa", "-tr(stress)/3, compression positive", f_pressure},
    {"von_mises", 1, MRN_VTK_FLOAT64, "Pa", "von Mises equivalent stress sqrt(3/2 s:s)", f_von_mises},
    {"eps_D", 1, MRN_VTK_FLOAT64, "", "deviatoric strain norm (000, Eq. 75)", f_eps_D},
    {"elastic_energy", 1, MRN_VTK_FLOAT64, "J", "elastic energy stored in the particle", f_elastic_energy},
    {"deformation_gradient", 9, MRN_VTK_FLOAT64, "", "F, row-major", f_F},
    {"material", 1, MRN_VTK_INT32, "", "material index (order of first use in the simulation)", f_material},
    {"id", 1, MRN_VTK_INT64, "", "particle id, stable through the run", f_id},
};
enum { FIELD_COUNT = sizeof fields / sizeof fields[0] };

static const char *const names[] = {"velocity", "displacement", "mass", "volume", "density", "stress",
                                    "strain", "pressure", "von_mises", "eps_D", "elastic_energy",
                                    "deformation_gradient", "material", "id", NULL};

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
    *out = (mrn_field_ref){f->name, f->ncomp, f->type, f, NULL};
    return 1;
  }
  const mrn_user_field *u = mrn_particles_user_field(&sim->particles, name);
  if (!u) return 0;
  *out = (mrn_field_ref){u->name, u->ncomp, MRN_VTK_FLOAT64, NULL, u};
  return 1;
}

void mrn_field_fill(const mrn_sim *sim, const mrn_field_ref *f, void *out) {
  if (f->builtin) {
    f->builtin->compute(sim, out);
    return;
  }
  const mrn_particles *ps = &sim->particles;
  double *o = out;
  FOR_PARTICLES(sim) memcpy(o + p * f->ncomp, ps->user + p * ps->user_stride + f->user->offset, sizeof(double) * f->ncomp);
}

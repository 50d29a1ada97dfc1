/* moraine: point forces on material points in the explicit step (see point_force.h). */
#include "solver/point_force.h"

#include <math.h>
#include <string.h>

#include "core/error.h"
#include "solver/simulation.h"
#include "transfer/stencils.h"

/* the force field, or NULL while no point has been loaded */
static const mrn_user_field *force_field(const mrn_sim *sim) {
  return mrn_particles_user_field(&sim->particles, MRN_POINT_FORCE_FIELD);
}

int mrn_sim_add_point_forces(mrn_sim *sim) {
  const mrn_user_field *uf = force_field(sim);
  if (!uf) return mrn_particles_add_user_field(&sim->particles, MRN_POINT_FORCE_FIELD, 3, 0.0, "N");
  if (uf->ncomp != 3)
    return mrn_error("particle field '%s' has %d components; point forces need it with 3", MRN_POINT_FORCE_FIELD,
                     uf->ncomp);
  return MRN_OK;
}

int mrn_sim_set_point_force(mrn_sim *sim, size_t p, const double f[3]) {
  mrn_particles *ps = &sim->particles;
  if (mrn_sim_add_point_forces(sim) != MRN_OK) return MRN_ERR;
  const mrn_user_field *uf = force_field(sim);
  double *v = ps->user + p * ps->user_stride + uf->offset;
  for (int d = 0; d < 3; d++) v[d] = d < sim->dim ? f[d] : 0.0;
  return MRN_OK;
}

void mrn_sim_clear_point_forces(mrn_sim *sim) {
  const mrn_user_field *uf = force_field(sim);
  mrn_particles *ps = &sim->particles;
  if (!uf) return;
  for (size_t p = 0; p < ps->n; p++)
    for (int k = 0; k < uf->ncomp; k++) ps->user[p * ps->user_stride + uf->offset + k] = 0.0;
}

void mrn_sim_set_load_factor(mrn_sim *sim, double factor) { sim->load_factor = factor; }

/* The loaded points' stencils, each handed to `visit` with the point's
 * scaled force. Loads are few (a tip, a loaded face), so the stencil is
 * rebuilt here rather than kept from P2G. */
#define FOR_EACH_LOADED(SUFFIX, BODY)                                               \
  {                                                                                 \
    stencil_##SUFFIX s;                                                             \
    for (size_t p = 0; p < ps->n; p++) {                                            \
      const double *fp = ps->user + p * ps->user_stride + uf->offset;               \
      if (fp[0] == 0.0 && fp[1] == 0.0 && fp[2] == 0.0) continue;                   \
      stencil_build_##SUFFIX(&sim->grid, &ko, ps->x + 3 * p, ps->vol0[p], &s);      \
      BODY                                                                          \
    }                                                                               \
  }

void mrn_point_forces_to_grid(mrn_sim *sim) {
  const mrn_user_field *uf = force_field(sim);
  if (!uf || uf->ncomp != 3 || sim->load_factor == 0.0) return;
  const mrn_particles *ps = &sim->particles;
  const mrn_kernel_options ko = mrn_sim_kernel_options(sim);
  const double lf = sim->load_factor;
  double *force = sim->grid.force;
#define SPREAD                                                                 \
  for (int c = 0; c < s.count; c++)                                            \
    for (int d = 0; d < 3; d++) force[3 * s.node[c] + d] += lf * s.N[c] * fp[d];
  if (sim->dim == 3) FOR_EACH_LOADED(3d, SPREAD) else FOR_EACH_LOADED(2d, SPREAD)
#undef SPREAD
}

double mrn_point_forces_work(const mrn_sim *sim, double dt) {
  const mrn_user_field *uf = force_field(sim);
  if (!uf || uf->ncomp != 3 || sim->load_factor == 0.0) return 0.0;
  const mrn_particles *ps = &sim->particles;
  const mrn_kernel_options ko = mrn_sim_kernel_options(sim);
  const double *vel = sim->grid.vel_new;
  double work = 0.0;
#define WORK                                                                     \
  for (int c = 0; c < s.count; c++)                                              \
    for (int d = 0; d < 3; d++) work += s.N[c] * fp[d] * vel[3 * s.node[c] + d];
  if (sim->dim == 3) FOR_EACH_LOADED(3d, WORK) else FOR_EACH_LOADED(2d, WORK)
#undef WORK
  return sim->load_factor * work * dt;
}

#include "solver/timestep.h"
#include "solver/dist.h"

#include <math.h>

#include "core/error.h"
#include "solver/simulation.h"
#include "transfer/cpdi.h"

#include <stdlib.h>

static const char *const kind_names[] = {"fixed", "a_tau", "cfl", "grid_cfl", "function"};

const char *mrn_dt_kind_name(mrn_dt_kind k) { return k <= MRN_DT_CALLBACK ? kind_names[k] : "?"; }

double mrn_grid_slowness_2d(mrn_sim *sim, const double *modulus);
double mrn_grid_slowness_3d(mrn_sim *sim, const double *modulus);

void mrn_dt_policy_cfl(mrn_dt_policy *p, mrn_dt_kind kind, double courant) {
  mrn_dt_policy_release(p);
  p->kind = kind;
  p->value = courant;
}

double mrn_dt_particle_critical_at(const mrn_sim *sim, long *fastest_particle, double *top_speed) {
  const mrn_particles *ps = &sim->particles;
  const double h = sim->grid.cell;
  double speed[MRN_MAX_MATERIALS], viscous = HUGE_VAL;
  /* with mass scaling the inertial density is f rho: the waves are sqrt(f)
   * slower and the kinematic viscosity eta / (f rho) is f times smaller */
  const double f = sim->mass_scaling, slower = f != 1.0 ? 1.0 / sqrt(f) : 1.0;
  for (int i = 0; i < sim->nmaterials; i++) {
    const mrn_material *m = sim->materials[i];
    speed[i] = (m->type->wave_speed ? m->type->wave_speed(m) : 0.0) * slower; /* (002, Eq. 34) */
    if (m->type->viscous_dt) viscous = fmin(viscous, f * m->type->viscous_dt(m, h)); /* h^2 / nu (002, Eq. 36) */
  }
  double fastest = 0.0, top = -1.0;
  long top_p = -1;
  const int cpdi = mrn_shape_is_cpdi(sim->shape);
  const double root_dim = sqrt((double)sim->dim);
  /* the CPDI stencil only reads the grid and the particles */
  const mrn_transfer tr = {.dim = sim->dim, .grid = (mrn_grid *)&sim->grid,
                           .particles = (mrn_particles *)&sim->particles, .kernel = mrn_sim_kernel_options(sim)};
  for (size_t p = 0; p < ps->n; p++) {
    const double *v = ps->v + 3 * p;
    double u = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), s = speed[ps->material[p]] + u;
    /* a CPDI domain's gradient beyond the hat's own largest, sqrt(dim) / h,
     * shortens the length a wave may cross in a step (transfer/cpdi.h) */
    if (cpdi) s *= fmax(1.0, h * mrn_cpdi_gradient_bound(&tr, p) / root_dim);
    if (s > fastest) fastest = s;
    if (u > top) {
      top = u;
      top_p = (long)p;
    }
  }
  /* the particles a source is about to make (and all there is in a run
   * that starts empty) */
  for (int k = 0; k < sim->nsources; k++) {
    const mrn_source *src = &sim->sources[k];
    const double *v = src->cfg.fn ? src->v : src->cfg.velocity;
    fastest = fmax(fastest, speed[src->cfg.material] + sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  }
  if (fastest_particle) *fastest_particle = top_p;
  if (top_speed) *top_speed = top_p >= 0 ? top : 0.0;
  double dt = fastest > 0.0 ? h / fastest : HUGE_VAL; /* (002, Eq. 35) */
  return fmin(dt, viscous);                              /* (002, Eq. 36) */
}

double mrn_dt_particle_critical(const mrn_sim *sim) { return mrn_dt_particle_critical_at(sim, NULL, NULL); }

double mrn_dt_grid_critical(mrn_sim *sim) {
  const mrn_particles *ps = &sim->particles;
  double *modulus = malloc((ps->n ? ps->n : 1) * sizeof(double));
  if (!modulus) return NAN;
  for (size_t p = 0; p < ps->n; p++) {
    const mrn_material *m = sim->materials[ps->material[p]];
    double c = m->type->wave_speed ? m->type->wave_speed(m) : 0.0;
    modulus[p] = ps->mass[p] / mrn_particle_volume(ps, p) * c * c; /* M_p = rho_p c_p^2 */
  }
  double slowness = sim->dim == 2 ? mrn_grid_slowness_2d(sim, modulus) : mrn_grid_slowness_3d(sim, modulus);
  free(modulus);
  /* the nodal masses of the inertial mass, mass_scaling m (solver/step.c) */
  return sim->grid.cell * slowness * sqrt(sim->mass_scaling); /* (001, Eq. 61) */
}

void mrn_dt_policy_release(mrn_dt_policy *p) {
  if (p->release && p->ctx) p->release(p->ctx);
  p->release = NULL;
  p->ctx = NULL;
  p->callback = NULL;
}

void mrn_dt_policy_fixed(mrn_dt_policy *p, double dt) {
  mrn_dt_policy_release(p);
  p->kind = MRN_DT_FIXED;
  p->value = dt;
}

void mrn_dt_policy_a_tau(mrn_dt_policy *p, double a_tau) {
  mrn_dt_policy_release(p);
  p->kind = MRN_DT_A_TAU;
  p->value = a_tau;
}

int mrn_dt_compute(mrn_sim *sim, double *out) {
  const mrn_dt_policy *p = &sim->dt_policy;
  double dt = NAN;
  switch (p->kind) {
  case MRN_DT_FIXED:
    dt = p->value;
    break;
  case MRN_DT_A_TAU: {
    double slowness = mrn_sim_slowness(sim);
    if (!isfinite(slowness))
      return mrn_error("time step a_tau: no material in the simulation to take rho and E from");
    dt = p->value * sim->grid.cell * slowness; /* (000, Eq. 29) */
    break;
  }
  case MRN_DT_CFL:
    dt = p->value * mrn_dt_particle_critical(sim); /* (002, Eq. 37) */
    break;
  case MRN_DT_GRID_CFL:
    dt = p->value * mrn_dt_grid_critical(sim);
    break;
  case MRN_DT_CALLBACK: {
    int rc = p->callback(p->ctx, sim, &dt);
    if (rc) return rc;
    break;
  }
  }
  /* the particles' and nodes' limits are those of every process; a bad
   * value on one makes all report it */
  if (sim->dist && (p->kind == MRN_DT_CFL || p->kind == MRN_DT_GRID_CFL)) {
    double v = dt > 0.0 ? dt : -1.0; /* NaN too */
    mrn_dist_reduce(sim, &v, 1, MRN_COMM_MIN);
    dt = v > 0.0 ? v : NAN;
  }
  if (!(dt > 0.0) || !isfinite(dt))
    return mrn_error_code(MRN_ERR_STATE, "step %ld: the %s time-step policy gave dt = %s (must be > 0)", sim->step + 1,
                          mrn_dt_kind_name(p->kind), mrn_num(dt).s);
  if (p->max > 0.0 && dt > p->max) dt = p->max;
  if (p->min > 0.0 && dt < p->min)
    return mrn_error_code(MRN_ERR_STATE,
                          "step %ld (t = %g s): the time step collapsed to %g s, below the minimum %g s",
                          sim->step + 1, sim->time, dt, p->min);
  *out = dt;
  return MRN_OK;
}

/* moraine: the implicit integrator driving mrn_run (sim:run), see implicit.h.
 *
 * mrn_implicit_advance makes one implicit step, shortened so that a run of
 * given duration ends on time, and books in the simulation's energy accounts what
 * the explicit diagnostics cannot see: the work of the point forces (into
 * work_external; gravity is in E_g already), the work of the forces holding
 * components at a prescribed velocity (into work_external too) and the energy the ghost penalty
 * removed (into work_damping, negative). The particle fields the diagnostics
 * read (v, x, F, stress, e_elastic, w_plastic) are kept by the step itself,
 * so W_MPM (000, Eq. 68) measures the implicit step's energy error. */
#include <math.h>

#include "core/error.h"
#include "implicit/implicit.h"
#include "implicit/implicit_internal.h"

/* -sum m g . x, the gravitational energy of the particles */
static double gravity_energy(const mrn_sim *sim) {
  const mrn_particles *ps = &sim->particles;
  double e = 0.0;
  for (size_t p = 0; p < ps->n; p++) e += mrn_sim_particle_gravity(sim, p);
  return e;
}

int mrn_implicit_advance(mrn_implicit *im, double t_end, mrn_implicit_history *h) {
  mrn_sim *sim = im->sim;
  double dt;
  int rc = mrn_implicit_next_dt(im, &dt);
  if (rc) return rc;
  const double remaining = t_end - sim->time;
  if (remaining <= 1e-9 * dt) return MRN_STEP_NONE; /* a round-off sliver is not worth a step */
  const double fixed = im->opt.dt;
  if (dt > remaining) im->opt.dt = remaining; /* the last step ends on time */
  const double ext0 = im->work_ext, con0 = im->work_con, ghost0 = im->ghost_work, eg0 = gravity_energy(sim);
  rc = mrn_implicit_step(im, &im->last);
  im->opt.dt = fixed;
  if (h) *h = im->last;
  if (rc) return rc;
  /* im->work_ext holds the work of gravity as well: take out -(change of E_g) */
  sim->work_external += (im->work_ext - ext0) + (gravity_energy(sim) - eg0) + (im->work_con - con0);
  sim->work_damping -= im->ghost_work - ghost0;
  return MRN_OK;
}

static int run_step(void *ctx, mrn_sim *sim, double t_end) {
  (void)sim;
  return mrn_implicit_advance(ctx, t_end, NULL);
}

static void forget_sim(void *ctx) { ((mrn_implicit *)ctx)->sim = NULL; }

void mrn_implicit_attach(mrn_implicit *im) {
  im->sim->integrator = (mrn_integrator){run_step, forget_sim, im};
}

void mrn_implicit_detach(mrn_implicit *im) {
  if (im && im->sim && im->sim->integrator.ctx == im) im->sim->integrator = (mrn_integrator){0};
}

const mrn_implicit_history *mrn_implicit_last(const mrn_implicit *im) { return &im->last; }

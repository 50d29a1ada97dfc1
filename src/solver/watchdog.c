#include "solver/watchdog.h"

#include <math.h>

#include "core/error.h"
#include "solver/dist.h"
#include "solver/simulation.h"
#include "solver/timestep.h"

void mrn_watchdog_default(mrn_watchdog *w) {
  w->energy = 1.0;
  w->dt = 4.0;
  w->speed = 1.0;
  w->every = 10;
}

void mrn_watchdog_start(mrn_watchdog_state *s, const mrn_sim *sim) {
  mrn_diagnostics d;
  mrn_sim_diagnostics(sim, &d);
  s->e_start = d.kinetic + d.elastic;
  s->last_step = sim->step;
}

/* a velocity face or constraint that moves: its work is not in W_MPM's books */
static int driven(const mrn_sim *sim) {
  for (int f = 0; f < 2 * sim->dim; f++) {
    const mrn_face_bc *b = &sim->boundary.face[f];
    if (b->kind == MRN_BC_VELOCITY && (b->velocity[0] != 0 || b->velocity[1] != 0 || b->velocity[2] != 0)) return 1;
  }
  for (int i = 0; i < sim->nconstraints; i++)
    for (int d = 0; d < 3; d++)
      if ((sim->constraints[i].mask >> d & 1u) && sim->constraints[i].velocity[d] != 0) return 1;
  return 0;
}

/* E_scale of watchdog.h */
static double energy_scale(const mrn_watchdog_state *s, const mrn_sim *sim, const mrn_diagnostics *d) {
  double fall = 0.0; /* |g| L = sum_i |g_i| size_i */
  for (int i = 0; i < sim->dim; i++) fall += fabs(sim->gravity[i]) * sim->grid.size[i];
  double scale = s->e_start + d->mass * fall + fabs(d->plastic) + fabs(d->friction) + fabs(d->damping) +
                 fabs(d->external) + fabs(d->inflow) + fabs(d->inflow_work) + fabs(d->outflow) +
                 d->bodies + fabs(d->bodies_work);
  const double crawl = 1e-3 * sim->grid.cell / sim->dt; /* a thousandth of a cell per step */
  return fmax(scale, 0.5 * d->mass * crawl * crawl);
}

/* ", pressed against the ymin wall" when particle p is within a cell of a wall face */
static const char *wall_note(const mrn_sim *sim, long p, char *buf, size_t len) {
  const double *x = sim->particles.x + 3 * p;
  buf[0] = '\0';
  for (int d = 0; d < sim->dim; d++)
    for (int side = 0; side < 2; side++) {
      mrn_bc_kind kind = sim->boundary.face[2 * d + side].kind;
      double face = sim->grid.origin[d] + side * sim->grid.size[d];
      if (kind != MRN_BC_FREE && kind != MRN_BC_PERIODIC && fabs(x[d] - face) <= sim->grid.cell)
        snprintf(buf, len, ", pressed against the %s wall", mrn_face_name(2 * d + side));
    }
  return buf;
}

static int trip(const mrn_sim *sim, const char *what, const char *cause) {
  return mrn_error_code(MRN_ERR_STATE, "step %ld (t = %g s): the watchdog stopped the run: %s; likely cause: %s",
                        sim->step, sim->time, what, cause);
}

static const char *dt_cause(double dt_ratio) {
  return dt_ratio > 1 ? "a time step above the stability limit (try dt = {cfl = 0.5})"
                      : "energy fed in by a material law outside its range, a hook, or a boundary";
}

/* the dt and speed tests of an explicit step; p is the fastest particle,
 * `limiting` when it sets the step's limit */
static int test_motion(mrn_watchdog_state *s, const mrn_sim *sim, double critical, long p, double speed,
                       int limiting) {
  const mrn_watchdog *w = &sim->watchdog;
  const double h = sim->grid.cell, dt = sim->dt;
  const double dt_ratio = isfinite(critical) ? dt / critical : 0.0, cells = speed * dt / h;
  char what[512], wall[64];
  s->peak_dt = fmax(s->peak_dt, dt_ratio);
  s->peak_speed = fmax(s->peak_speed, cells);
  if (limiting && w->dt > 0 && dt_ratio > w->dt) {
    snprintf(what, sizeof what, "the step dt = %g s is %.3g times the particle CFL estimate h / max(c + |v|) = %g s "
             "(bound %g; the fastest particle %lld moves at %g m/s)", dt, dt_ratio, critical, w->dt,
             (long long)sim->particles.id[p], speed);
    return trip(sim, what, dt_cause(dt_ratio));
  }
  if (w->speed > 0 && cells > w->speed) {
    const double *x = sim->particles.x + 3 * p;
    snprintf(what, sizeof what, "particle %lld at (%g, %g, %g) moves at %g m/s, %.3g cells per step (bound %g; "
             "h = %g m, dt = %g s)%s", (long long)sim->particles.id[p], x[0], x[1], x[2], speed, cells, w->speed,
             h, dt, wall_note(sim, p, wall, sizeof wall));
    return trip(sim, what, dt_cause(dt_ratio));
  }
  return MRN_OK;
}

/* the energy test: W_MPM (000, Eq. 68) against E_scale */
static int test_energy(mrn_watchdog_state *s, const mrn_sim *sim, double dt_ratio) {
  const mrn_watchdog *w = &sim->watchdog;
  if (!(w->energy > 0) || !sim->energy_ref_set || driven(sim)) return MRN_OK;
  mrn_diagnostics d;
  mrn_sim_energies(sim, &d);
  const double scale = energy_scale(s, sim, &d);
  if (!(scale > 0.0)) return MRN_OK; /* no particles yet (a source about to begin): nothing to judge */
  const double ratio = d.mpm_error / scale;
  s->peak_energy = fmax(s->peak_energy, ratio);
  if (ratio <= w->energy) return MRN_OK;
  char what[512];
  snprintf(what, sizeof what, "the energy the discretisation created, W_MPM = %g J, is %.3g times the energy "
           "scale %g J (bound %g; E_k = %g J, E_el = %g J; dt = %.3g x the CFL estimate)", d.mpm_error, ratio,
           scale, w->energy, d.kinetic, d.elastic, dt_ratio);
  return trip(sim, what, dt_cause(dt_ratio));
}

int mrn_watchdog_check(mrn_watchdog_state *s, const mrn_sim *sim, int force) {
  const mrn_watchdog *w = &sim->watchdog;
  if (!(w->energy > 0 || w->dt > 0 || w->speed > 0)) return MRN_OK;
  if (!force && sim->step - s->last_step < w->every) return MRN_OK;
  s->last_step = sim->step;
  s->checks++;
  double speed;
  long p;
  double critical = mrn_dt_particle_critical_at(sim, &p, &speed);
  /* in a distributed run: the limit of every process; each judges the
   * speeds of its own particles, and the process of the limiting particle
   * the step (solver/dist.h), and all of them the energy */
  double global = critical;
  mrn_dist_reduce(sim, &global, 1, MRN_COMM_MIN);
  int rc = MRN_OK;
  /* an implicit step may exceed the explicit limits by design (001) */
  if (sim->integrator.step == NULL && sim->particles.n > 0)
    rc = test_motion(s, sim, global, p, speed, critical == global);
  const int rc_energy = test_energy(s, sim, isfinite(global) ? sim->dt / global : 0.0);
  return rc != MRN_OK ? rc : rc_energy;
}

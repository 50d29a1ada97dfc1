#include "solver/timestep.h"

#include <math.h>

#include "core/error.h"
#include "solver/simulation.h"

static const char *const kind_names[] = {"fixed", "a_tau", "function"};

const char *mrn_dt_kind_name(mrn_dt_kind k) { return k <= MRN_DT_CALLBACK ? kind_names[k] : "?"; }

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
  case MRN_DT_CALLBACK: {
    int rc = p->callback(p->ctx, sim, &dt);
    if (rc) return rc;
    break;
  }
  }
  if (!(dt > 0.0) || !isfinite(dt))
    return mrn_error_code(MRN_ERR_STATE, "step %ld: the %s time-step policy gave dt = %g (must be > 0)", sim->step + 1,
                          mrn_dt_kind_name(p->kind), dt);
  if (p->max > 0.0 && dt > p->max) dt = p->max;
  if (p->min > 0.0 && dt < p->min)
    return mrn_error_code(MRN_ERR_STATE,
                          "step %ld (t = %g s): the time step collapsed to %g s, below the minimum %g s",
                          sim->step + 1, sim->time, dt, p->min);
  *out = dt;
  return MRN_OK;
}

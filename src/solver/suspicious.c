#include "solver/suspicious.h"

#include <math.h>

#include "core/warn.h"
#include "solver/timestep.h"

void mrn_suspicious_run(const mrn_sim *sim) {
  const mrn_dt_policy *p = &sim->dt_policy;
  if (p->kind == MRN_DT_FIXED) {
    /* the particle CFL step h / max(c + |v|) (002, Eqs. 34-37) with C = 1:
     * an explicit step above it amplifies the fastest wave */
    double critical = mrn_dt_particle_critical(sim);
    if (isfinite(critical) && p->value > critical)
      mrn_warning("dt_above_cfl",
               "the fixed time step %g s is %.3g times the CFL estimate %g s (h / max(c + |v|)); the run may become "
               "unstable",
               p->value, p->value / critical, critical);
  } else if ((p->kind == MRN_DT_CFL || p->kind == MRN_DT_GRID_CFL) && p->value > 1) {
    mrn_warning("courant_above_one", "the Courant number %g is above 1: explicit steps beyond the CFL limit are unstable",
             p->value);
  }
}

void mrn_suspicious_seed(const mrn_sim *sim, int per_axis, long count) {
  if (per_axis == 1 && count > 0)
    mrn_warning("one_particle_per_cell",
             "%ld particles seeded one per cell: a particle crossing a cell boundary then makes grid-crossing noise; "
             "per_axis = 2 or more is usual",
             count);
  (void)sim;
}

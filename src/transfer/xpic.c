#include "transfer/xpic.h"

#include <string.h>

#include "solver/simulation.h"
#include "transfer/kernels.h"

void mrn_xpic_smooth(mrn_sim *sim, double *pscratch) {
  mrn_grid *g = &sim->grid;
  const int m = sim->scheme.xpic_order;
  const size_t len = 3 * g->n;
  /* cur = S^(k-1) V^G, starting with k = 1 */
  memcpy(g->work, g->vel, len * sizeof(double));
  for (size_t i = 0; i < len; i++) g->vel_star[i] = m * g->work[i];
  double binom = m;
  for (int k = 2; k <= m; k++) {
    mrn_grid_to_particles(sim, sim->dim, g->work, pscratch);
    mrn_particles_to_grid(sim, sim->dim, pscratch, g->work);
    /* the smoothed field obeys the same face conditions as the velocity */
    mrn_boundary_apply(&sim->boundary, g, sim->mass_floor, g->work, 0);
    binom = binom * (m - k + 1) / k;
    double sign = (k % 2 == 0) ? -1.0 : 1.0; /* (-1)^(k+1) */
    for (size_t i = 0; i < len; i++) g->vel_star[i] += sign * binom * g->work[i];
  }
}

#include "transfer/xpic.h"

#include <string.h>

#include "transfer/kernels.h"

void mrn_xpic_smooth(mrn_transfer *tr, double *pscratch) {
  mrn_grid *g = tr->grid;
  const int m = tr->scheme->xpic_order;
  const size_t len = 3 * g->n;
  /* cur = S^(k-1) V^G, starting with k = 1 */
  memcpy(g->work, g->vel, len * sizeof(double));
  for (size_t i = 0; i < len; i++) g->vel_star[i] = m * g->work[i];
  double binom = m, before = m; /* before: sum_{j < k} (-1)^(j+1) C(m, j) */
  for (int k = 2; k <= m; k++) {
    mrn_grid_to_particles(tr, g->work, pscratch);
    mrn_particles_to_grid(tr, pscratch, g->work);
    if (tr->sum_nodal) tr->sum_nodal(tr->sum_ctx, g->work, 3);
    /* the smoothed field obeys the same conditions as the velocity: at a
     * held node every S^k V is the held value, and so is V*. A hold here
     * enters this term and, through S (which keeps the momentum), every
     * later one: its weight in V* is 1 - before */
    if (tr->hold) tr->hold(tr->sum_ctx, g->work, 1.0 - before);
    else mrn_boundary_apply(tr->boundary, g, tr->mass_floor, g->work, 0);
    binom = binom * (m - k + 1) / k;
    const double sign = (k % 2 == 0) ? -1.0 : 1.0; /* (-1)^(k+1) */
    for (size_t i = 0; i < len; i++) g->vel_star[i] += sign * binom * g->work[i];
    before += sign * binom;
  }
}

#include "transfer/volumetric.h"

#include "core/parallel.h"
#include "transfer/kernels.h"

void mrn_volumetric_average(mrn_transfer *tr, double *L, double *q) {
  const mrn_particles *ps = tr->particles;
  mrn_grid *g = tr->grid;
  const int dim = tr->dim;
  const long n = (long)ps->n;
  /* P_m (mass-weighted, over the nodal mass) of V div / m and V / m gives
   * sum N V div / m_i and sum N V / m_i: their ratio is the volume-weighted
   * nodal divergence whatever the nodal mass holds (mass scaling) */
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < n; p++) {
    const double *Lp = L + 9 * p;
    const double m = ps->mass[p];
    const double w = m > 0.0 ? mrn_particle_volume_dim(ps, (size_t)p, dim) / m : 0.0;
    q[3 * p] = w * (Lp[0] + Lp[4] + Lp[8]);
    q[3 * p + 1] = w;
    q[3 * p + 2] = 0.0;
  }
  mrn_particles_to_grid(tr, q, g->work);
  if (tr->sum_nodal) tr->sum_nodal(tr->sum_ctx, g->work, 3);
  const long nodes = (long)g->n;
#pragma omp parallel for schedule(static) if (nodes > MRN_OMP_MIN_NODES)
  for (long i = 0; i < nodes; i++) {
    double *v = g->work + 3 * i;
    const int reached = v[1] > 0.0;
    v[0] = reached ? v[0] / v[1] : 0.0;
    v[1] = reached;
  }
  mrn_grid_to_particles(tr, g->work, q);
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < n; p++) {
    double *Lp = L + 9 * p;
    if (!(q[3 * p + 1] > 0.0)) continue; /* no node reached: the particle's own */
    const double c = (q[3 * p] / q[3 * p + 1] - (Lp[0] + Lp[4] + Lp[8])) / dim;
    Lp[0] += c;
    Lp[4] += c;
    if (dim == 3) Lp[8] += c;
  }
}

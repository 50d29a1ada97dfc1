/* moraine: nodal averages for the grid-averaged CFL estimate (001, Eqs.
 * 58-61); included with DIM = 2 or 3 like the transfer kernels. */
#include <math.h>
#include <stdlib.h>

#include "solver/simulation.h"
#include "transfer/stencil.h"

/* min over nodes of sqrt(m_A / (V_A M_A)) = 1 / (nodal wave speed), with
 * m_A, V_A, M_A = sum_p N_A {m_p, V_p, M_p} and M_p = rho_p c_p^2 the
 * particle's P-wave modulus (001, Eqs. 58-60). HUGE_VAL without particles. */
double KNAME(mrn_grid_slowness)(mrn_sim *sim, const double *modulus) {
  const mrn_grid *g = &sim->grid;
  const mrn_particles *ps = &sim->particles;
  mrn_kernel_options ko = mrn_sim_kernel_options(sim);
  ko.mls_gradient = 0; /* values only */
  double *acc = calloc(3 * g->n, sizeof(double)); /* m, V, M per node */
  if (!acc) return NAN;
  KNAME(stencil) s;
  for (size_t p = 0; p < ps->n; p++) {
    KNAME(stencil_build)(g, &ko, ps->x + 3 * p, ps->vol0[p], &s);
    for (int c = 0; c < s.count; c++) {
      double *a = acc + 3 * s.node[c];
      a[0] += s.N[c] * ps->mass[p];
      a[1] += s.N[c] * mrn_particle_volume(ps, p);
      a[2] += s.N[c] * modulus[p];
    }
  }
  double best = HUGE_VAL;
  for (size_t i = 0; i < g->n; i++) {
    const double *a = acc + 3 * i;
    if (a[0] > sim->mass_floor && a[1] > 0 && a[2] > 0) {
      double v = sqrt(a[0] / (a[1] * a[2])); /* (001, Eq. 61) */
      if (v < best) best = v;
    }
  }
  free(acc);
  return best;
}

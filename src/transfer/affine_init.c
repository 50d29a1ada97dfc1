/* moraine: initial grad v and APIC C for particles given initial velocities
 * (000 §3.2, last paragraph): repeat the Taylor transfer (000, Eqs. 19-22)
 * until the particles' grad v stops changing; APIC's C takes the same value. */
#include <math.h>
#include <string.h>

#include "core/parallel.h"

#include "solver/simulation.h"
#include "transfer/kernels.h"

#define MAX_ITERATIONS 100

typedef struct taylor_ctx {
  double *affine;
  double change, scale; /* max |grad v - affine|, max |grad v| */
} taylor_ctx;

/* gradient sink: the new grad v of a chunk replaces its affine matrices,
 * noting how much they changed (maxima: the same for any order of chunks) */
static long take_gradient(void *ctx, size_t lo, size_t hi, const double *L) {
  taylor_ctx *t = ctx;
  double change = 0.0, scale = 0.0;
  double *A = t->affine + 9 * lo;
  for (size_t k = 0; k < 9 * (hi - lo); k++) {
    change = fmax(change, fabs(L[k] - A[k]));
    scale = fmax(scale, fabs(L[k]));
  }
  memcpy(A, L, 9 * (hi - lo) * sizeof(double));
#pragma omp critical(mrn_taylor_change)
  {
    t->change = fmax(t->change, change);
    t->scale = fmax(t->scale, scale);
  }
  return -1;
}

int mrn_sim_init_affine(mrn_sim *sim) {
  mrn_particles *ps = &sim->particles;
  mrn_grid *g = &sim->grid;
  const mrn_grid_velocity_kind saved = sim->scheme.grid_velocity;
  sim->scheme.grid_velocity = MRN_VGRID_TAYLOR;
  memset(ps->affine, 0, 9 * ps->n * sizeof(double));
  int it;
  for (it = 1; it <= MAX_ITERATIONS; it++) {
    mrn_p2g(sim, sim->dim, 1, 0); /* (000, Eq. 19) with the current grad v */
    for (size_t i = 0; i < g->n; i++)
      for (int d = 0; d < 3; d++)
        g->vel[3 * i + d] = g->mass[i] > sim->mass_floor ? g->mom[3 * i + d] / g->mass[i] : 0.0;
    taylor_ctx t = {ps->affine, 0.0, 0.0};
    const mrn_gradient_sink sink = {take_gradient, &t, MRN_PHASE_G2P};
    mrn_gradient(sim, sim->dim, g->vel, &sink); /* (000, Eq. 22) */
    if (t.change <= 1e-15 * t.scale || t.scale == 0.0) break;
  }
  sim->scheme.grid_velocity = saved;
  sim->affine_pending = 0;
  return it;
}

/* moraine: initial grad v and APIC C for particles given initial velocities
 * (000 §3.2, last paragraph): repeat the Taylor transfer (000, Eqs. 19-22)
 * until the particles' grad v stops changing; APIC's C takes the same value. */
#include <math.h>
#include <string.h>

#include "solver/simulation.h"
#include "transfer/kernels.h"

#define MAX_ITERATIONS 100

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
    mrn_gradient(sim, sim->dim, g->vel); /* (000, Eq. 22) into gradv */
    double change = 0.0, scale = 0.0;
    for (size_t k = 0; k < 9 * ps->n; k++) {
      change = fmax(change, fabs(ps->gradv[k] - ps->affine[k]));
      scale = fmax(scale, fabs(ps->gradv[k]));
    }
    memcpy(ps->affine, ps->gradv, 9 * ps->n * sizeof(double));
    if (change <= 1e-15 * scale || scale == 0.0) break;
  }
  sim->scheme.grid_velocity = saved;
  memset(ps->gradv, 0, 9 * ps->n * sizeof(double));
  sim->affine_pending = 0;
  return it;
}

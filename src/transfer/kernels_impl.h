/* moraine: body of the transfer kernels; included with DIM = 2 or 3 and
 * KNAME(x) naming the specialised functions. See kernels.h. */
#include <string.h>

#include "core/parallel.h"
#include "core/tensor.h"

#include "solver/simulation.h"
#include "transfer/kernels.h"
#include "transfer/stencil.h"

void KNAME(mrn_p2g)(mrn_sim *sim, int momentum, int force) {
  mrn_grid *g = &sim->grid;
  const mrn_particles *ps = &sim->particles;
  if (momentum) {
    memset(g->mass, 0, g->n * sizeof(double));
    memset(g->mom, 0, 3 * g->n * sizeof(double));
  }
  if (force) memset(g->force, 0, 3 * g->n * sizeof(double));
  KNAME(stencil) s;
  for (size_t p = 0; p < ps->n; p++) {
    const double *x = ps->x + 3 * p;
    KNAME(stencil_build)(g, sim->shape, x, &s);
    const double m = ps->mass[p];
    const double *v = ps->v + 3 * p;
    const double *sig = ps->stress + 6 * p;
    const double vol = ps->vol[p];
    for (int c = 0; c < s.count; c++) {
      const size_t n = s.node[c];
      if (momentum) {
        const double wm = s.N[c] * m;
        g->mass[n] += wm;
        for (int d = 0; d < DIM; d++) g->mom[3 * n + d] += wm * v[d];
      }
      if (force) {
        /* f_a = -V sigma_ab dN/dx_b */
        for (int a = 0; a < DIM; a++) {
          double f = 0.0;
          for (int b = 0; b < DIM; b++) f += sig[sym_index(a, b)] * s.dN[c][b];
          g->force[3 * n + a] -= vol * f;
        }
      }
    }
  }
}

void KNAME(mrn_gradient)(mrn_sim *sim, const double *gvel) {
  const mrn_grid *g = &sim->grid;
  mrn_particles *ps = &sim->particles;
  const long n = (long)ps->n;
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < n; p++) {
    KNAME(stencil) s;
    KNAME(stencil_build)(g, sim->shape, ps->x + 3 * p, &s);
    double L[9] = {0};
    for (int c = 0; c < s.count; c++) {
      const double *vi = gvel + 3 * s.node[c];
      for (int a = 0; a < DIM; a++)
        for (int b = 0; b < DIM; b++) L[3 * a + b] += vi[a] * s.dN[c][b];
    }
    memcpy(ps->gradv + 9 * p, L, sizeof L);
  }
}

void KNAME(mrn_g2p)(mrn_sim *sim, double dt, double *dx) {
  const mrn_grid *g = &sim->grid;
  mrn_particles *ps = &sim->particles;
  const mrn_scheme *sc = &sim->scheme;
  const double X = sc->velocity_update == MRN_VUPDATE_PIC ? 0.0
                   : sc->velocity_update == MRN_VUPDATE_FLIP ? 1.0 : sc->flip_fraction;
  const int by_particle = sc->position_update == MRN_XUPDATE_PARTICLE;
  const long n = (long)ps->n;
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < n; p++) {
    KNAME(stencil) s;
    double *x = ps->x + 3 * p;
    double *v = ps->v + 3 * p;
    KNAME(stencil_build)(g, sim->shape, x, &s);
    double v_pic[3] = {0, 0, 0}, a_p[3] = {0, 0, 0};
    for (int c = 0; c < s.count; c++) {
      const size_t node = s.node[c];
      for (int d = 0; d < DIM; d++) {
        v_pic[d] += s.N[c] * g->vel_new[3 * node + d]; /* (000, Eq. 31) */
        a_p[d] += s.N[c] * g->acc[3 * node + d];
      }
    }
    double step[3] = {0, 0, 0};
    for (int d = 0; d < DIM; d++) {
      double v_flip = v[d] + a_p[d] * dt; /* (000, Eq. 33) */
      double v_new = X * v_flip + (1.0 - X) * v_pic[d]; /* (000, Eq. 37) */
      /* (000, Eq. 32) with the grid velocity, Eqs. 36/38 with the particle's */
      step[d] = (by_particle ? v_new : v_pic[d]) * dt;
      v[d] = v_new;
    }
    if (dx) {
      for (int d = 0; d < 3; d++) dx[3 * p + d] = step[d];
    } else {
      for (int d = 0; d < DIM; d++) x[d] += step[d];
    }
  }
}

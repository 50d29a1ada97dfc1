/* moraine: body of the transfer kernels; included with DIM = 2 or 3 and
 * KNAME(x) naming the specialised functions. See kernels.h. */
#include <string.h>

#include "core/parallel.h"
#include "core/tensor.h"
#include "solver/simulation.h"
#include "transfer/kernels.h"
#include "transfer/stencil.h"

static inline mrn_kernel_options KNAME(kernel_options)(const mrn_sim *sim) {
  mrn_kernel_options o = {sim->shape, sim->kernel_boundary, sim->scheme.mls_gradient, 0};
  for (int d = 0; d < DIM; d++)
    if (mrn_boundary_periodic(&sim->boundary, d)) o.periodic |= 1u << d;
  return o;
}

void KNAME(mrn_p2g)(mrn_sim *sim, int momentum, int force) {
  mrn_grid *g = &sim->grid;
  const mrn_particles *ps = &sim->particles;
  const mrn_kernel_options ko = KNAME(kernel_options)(sim);
  const int affine = sim->scheme.grid_velocity != MRN_VGRID_PLAIN;
  if (momentum) {
    memset(g->mass, 0, g->n * sizeof(double));
    memset(g->mom, 0, 3 * g->n * sizeof(double));
  }
  if (force) memset(g->force, 0, 3 * g->n * sizeof(double));
  KNAME(stencil) s;
  for (size_t p = 0; p < ps->n; p++) {
    KNAME(stencil_build)(g, &ko, ps->x + 3 * p, ps->vol0[p], &s);
    const double m = ps->mass[p];
    const double *v = ps->v + 3 * p;
    const double *A = ps->affine + 9 * p;
    const double *sig = ps->stress + 6 * p;
    const double vol = ps->vol[p];
    for (int c = 0; c < s.count; c++) {
      const size_t n = s.node[c];
      if (momentum) {
        const double wm = s.N[c] * m;
        g->mass[n] += wm;
        for (int a = 0; a < DIM; a++) {
          double va = v[a];
          /* (000, Eqs. 19-20 and 23-24): v_p + A_p (x_i - x_p), A = grad v or C */
          if (affine)
            for (int b = 0; b < DIM; b++) va += A[3 * a + b] * s.offset[c][b];
          g->mom[3 * n + a] += wm * va;
        }
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
  const mrn_kernel_options ko = KNAME(kernel_options)(sim);
  const long n = (long)ps->n;
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < n; p++) {
    KNAME(stencil) s;
    KNAME(stencil_build)(g, &ko, ps->x + 3 * p, ps->vol0[p], &s);
    double L[9] = {0};
    for (int c = 0; c < s.count; c++) {
      const double *vi = gvel + 3 * s.node[c];
      for (int a = 0; a < DIM; a++)
        for (int b = 0; b < DIM; b++) L[3 * a + b] += vi[a] * s.dN[c][b];
    }
    memcpy(ps->gradv + 9 * p, L, sizeof L);
  }
}

/* C = B D^-1 (000, Eqs. 25-27) from the stencil and the updated velocities */
static inline void KNAME(apic_matrix)(const KNAME(stencil) *s, const double *gvel, double C[9]) {
  double B[DIM][DIM] = {{0}}, D[DIM][DIM] = {{0}};
  for (int c = 0; c < s->count; c++) {
    const double *vi = gvel + 3 * s->node[c];
    for (int a = 0; a < DIM; a++)
      for (int b = 0; b < DIM; b++) {
        B[a][b] += s->N[c] * vi[a] * s->offset[c][b];
        D[a][b] += s->N[c] * s->offset[c][a] * s->offset[c][b];
      }
  }
  double Di[DIM][DIM];
#if DIM == 2
  double det = D[0][0] * D[1][1] - D[0][1] * D[1][0];
  Di[0][0] = D[1][1] / det;
  Di[1][1] = D[0][0] / det;
  Di[0][1] = -D[0][1] / det;
  Di[1][0] = -D[1][0] / det;
#else
  double det = D[0][0] * (D[1][1] * D[2][2] - D[1][2] * D[2][1]) - D[0][1] * (D[1][0] * D[2][2] - D[1][2] * D[2][0]) +
               D[0][2] * (D[1][0] * D[2][1] - D[1][1] * D[2][0]);
  Di[0][0] = (D[1][1] * D[2][2] - D[1][2] * D[2][1]) / det;
  Di[0][1] = (D[0][2] * D[2][1] - D[0][1] * D[2][2]) / det;
  Di[0][2] = (D[0][1] * D[1][2] - D[0][2] * D[1][1]) / det;
  Di[1][0] = (D[1][2] * D[2][0] - D[1][0] * D[2][2]) / det;
  Di[1][1] = (D[0][0] * D[2][2] - D[0][2] * D[2][0]) / det;
  Di[1][2] = (D[0][2] * D[1][0] - D[0][0] * D[1][2]) / det;
  Di[2][0] = (D[1][0] * D[2][1] - D[1][1] * D[2][0]) / det;
  Di[2][1] = (D[0][1] * D[2][0] - D[0][0] * D[2][1]) / det;
  Di[2][2] = (D[0][0] * D[1][1] - D[0][1] * D[1][0]) / det;
#endif
  memset(C, 0, 9 * sizeof(double));
  for (int a = 0; a < DIM; a++)
    for (int b = 0; b < DIM; b++) {
      double v = 0.0;
      for (int k = 0; k < DIM; k++) v += B[a][k] * Di[k][b];
      C[3 * a + b] = v;
    }
}

void KNAME(mrn_g2p)(mrn_sim *sim, double dt, double *dx) {
  const mrn_grid *g = &sim->grid;
  mrn_particles *ps = &sim->particles;
  const mrn_scheme *sc = &sim->scheme;
  const mrn_kernel_options ko = KNAME(kernel_options)(sim);
  const mrn_velocity_update_kind vu = sc->velocity_update;
  const mrn_position_update_kind xu = sc->position_update;
  const double X = vu == MRN_VUPDATE_FLIP ? 1.0 : vu == MRN_VUPDATE_BLEND ? sc->flip_fraction : 0.0;
  const mrn_grid_velocity_kind gv = sc->grid_velocity;
  const long n = (long)ps->n;
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < n; p++) {
    KNAME(stencil) s;
    double *x = ps->x + 3 * p;
    double *v = ps->v + 3 * p;
    KNAME(stencil_build)(g, &ko, x, ps->vol0[p], &s);
    double v_pic[3] = {0, 0, 0}, a_p[3] = {0, 0, 0}, v_star[3] = {0, 0, 0};
    for (int c = 0; c < s.count; c++) {
      const size_t node = s.node[c];
      for (int d = 0; d < DIM; d++) {
        v_pic[d] += s.N[c] * g->vel_new[3 * node + d]; /* (000, Eq. 31) */
        a_p[d] += s.N[c] * g->acc[3 * node + d];
        if (vu == MRN_VUPDATE_XPIC) v_star[d] += s.N[c] * g->vel_star[3 * node + d];
      }
    }
    if (gv == MRN_VGRID_AFFINE) {
      KNAME(apic_matrix)(&s, g->vel_new, ps->affine + 9 * p);
    } else if (gv == MRN_VGRID_TAYLOR) {
      double *Lp = ps->affine + 9 * p; /* (000, Eq. 22) with the updated velocities */
      memset(Lp, 0, 9 * sizeof(double));
      for (int c = 0; c < s.count; c++) {
        const double *vi = g->vel_new + 3 * s.node[c];
        for (int a = 0; a < DIM; a++)
          for (int b = 0; b < DIM; b++) Lp[3 * a + b] += vi[a] * s.dN[c][b];
      }
    }
    double step[3] = {0, 0, 0};
    for (int d = 0; d < DIM; d++) {
      double v_new;
      if (vu == MRN_VUPDATE_XPIC) {
        v_new = v_star[d] + a_p[d] * dt; /* (000, Eq. 40): V - (I - G P)^m V = G V* */
      } else {
        double v_flip = v[d] + a_p[d] * dt;              /* (000, Eq. 33) */
        v_new = X * v_flip + (1.0 - X) * v_pic[d];       /* (000, Eqs. 31, 37) */
      }
      switch (xu) {
      case MRN_XUPDATE_GRID: step[d] = v_pic[d] * dt; break;    /* (000, Eq. 32) */
      case MRN_XUPDATE_PARTICLE: step[d] = v_new * dt; break;   /* (000, Eqs. 36, 38) */
      case MRN_XUPDATE_XPIC:                                     /* (000, Eq. 41) */
        step[d] = dt * (v_pic[d] - 0.5 * a_p[d] * dt - 0.5 * (v[d] - v_star[d]));
        break;
      }
      v[d] = v_new;
    }
    if (dx) {
      for (int d = 0; d < 3; d++) dx[3 * p + d] = step[d];
    } else {
      for (int d = 0; d < DIM; d++) x[d] += step[d];
    }
  }
}

void KNAME(mrn_grid_to_particles)(mrn_sim *sim, const double *gvel, double *pvel) {
  const mrn_grid *g = &sim->grid;
  const mrn_particles *ps = &sim->particles;
  const mrn_kernel_options ko = KNAME(kernel_options)(sim);
  const long n = (long)ps->n;
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < n; p++) {
    KNAME(stencil) s;
    KNAME(stencil_build)(g, &ko, ps->x + 3 * p, ps->vol0[p], &s);
    double v[3] = {0, 0, 0};
    for (int c = 0; c < s.count; c++)
      for (int d = 0; d < DIM; d++) v[d] += s.N[c] * gvel[3 * s.node[c] + d];
    for (int d = 0; d < 3; d++) pvel[3 * p + d] = v[d];
  }
}

void KNAME(mrn_particles_to_grid)(mrn_sim *sim, const double *pvel, double *gvel) {
  const mrn_grid *g = &sim->grid;
  const mrn_particles *ps = &sim->particles;
  const mrn_kernel_options ko = KNAME(kernel_options)(sim);
  memset(gvel, 0, 3 * g->n * sizeof(double));
  KNAME(stencil) s;
  for (size_t p = 0; p < ps->n; p++) {
    KNAME(stencil_build)(g, &ko, ps->x + 3 * p, ps->vol0[p], &s);
    for (int c = 0; c < s.count; c++) {
      const double wm = s.N[c] * ps->mass[p];
      for (int d = 0; d < DIM; d++) gvel[3 * s.node[c] + d] += wm * pvel[3 * p + d];
    }
  }
  for (size_t i = 0; i < g->n; i++) {
    double m = g->mass[i];
    for (int d = 0; d < 3; d++) gvel[3 * i + d] = m > sim->mass_floor ? gvel[3 * i + d] / m : 0.0;
  }
}

/* moraine: kernel consistency (002, Eqs. 38-41) for every shape function and
 * every treatment of the grid faces, with particles everywhere in the grid,
 * including the cells next to the faces:
 *   sum N = 1, sum N x_i = x_p, sum grad N = 0, sum x_i (x) grad N = I.
 * With the WLS correction, the boundary-modified kernels and the extended
 * (ghost-node) grid they hold to 1e-12; the truncated kernels violate them
 * next to the faces, which the test shows.
 * uGIMP's factored 1D form, which every stencil uses (MRN_GIMP_FACTORED),
 * against the plain piecewise form: within 4 DBL_EPSILON (|xi| + 1) for the
 * weights and that over lp for the derivatives (the factored form rounds
 * xi - lp, the piecewise one forms xi - node exactly: half an ulp of xi,
 * which the derivative's slope 1/lp magnifies), weights never negative,
 * and the quadratic B-spline at lp = 1/2. */
#include <float.h>
#include <stdlib.h>

#include "check.h"
#include "shape/shape.h"

#include "transfer/stencils.h"

static double rnd(unsigned *s) {
  *s = *s * 1664525u + 1013904223u;
  return (*s >> 8) / 16777216.0;
}

typedef struct errors {
  double unity, linear, grad_sum, grad_linear;
} errors;

static void accumulate(errors *e, int dim, int count, const double *N, const double *dN, const double *off) {
  double sN = 0, sx[3] = {0}, sg[3] = {0}, sxg[3][3] = {{0}};
  for (int c = 0; c < count; c++) {
    sN += N[c];
    for (int a = 0; a < dim; a++) {
      sx[a] += N[c] * off[c * dim + a]; /* sum N (x_i - x_p) = 0  <=>  sum N x_i = x_p */
      sg[a] += dN[c * dim + a];
      for (int b = 0; b < dim; b++) sxg[a][b] += off[c * dim + a] * dN[c * dim + b];
    }
  }
  e->unity = fmax(e->unity, fabs(sN - 1));
  for (int a = 0; a < dim; a++) {
    e->linear = fmax(e->linear, fabs(sx[a]));
    e->grad_sum = fmax(e->grad_sum, fabs(sg[a]));
    for (int b = 0; b < dim; b++) e->grad_linear = fmax(e->grad_linear, fabs(sxg[a][b] - (a == b)));
  }
}

/* errors over particles sampled in the whole domain (boundary cells included) */
static errors sweep(int dim, mrn_shape_kind shape, mrn_kernel_boundary mode, int boundary_only) {
  mrn_grid g;
  double origin[3] = {-1.0, 0.5, 2.0}, size[3] = {1.0, 0.8, 0.6};
  mrn_grid_init(&g, dim, origin, size, 0.1);
  mrn_kernel_options opt = {shape, mode, 0, 0};
  errors e = {0, 0, 0, 0};
  unsigned seed = 7u + shape * 13u + mode * 101u;
  const double vol0 = pow(0.05, dim); /* 2 particles per cell axis */
  for (int i = 0; i < 4000; i++) {
    double x[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) {
      double u = rnd(&seed);
      if (boundary_only || i % 3 == 0) u = (i & 1) ? 1.0 - 0.1 * u : 0.1 * u; /* within a cell of a face */
      if (i < 2) u = i; /* exactly on the faces */
      x[d] = origin[d] + u * g.size[d];
    }
    if (dim == 2) {
      stencil_2d s;
      stencil_build_2d(&g, &opt, x, vol0, &s);
      accumulate(&e, 2, s.count, s.N, &s.dN[0][0], &s.offset[0][0]);
    } else {
      stencil_3d s;
      stencil_build_3d(&g, &opt, x, vol0, &s);
      accumulate(&e, 3, s.count, s.N, &s.dN[0][0], &s.offset[0][0]);
    }
  }
  mrn_grid_free(&g);
  return e;
}

/* uGIMP 1D: factored against piecewise, at random positions and where a
 * branch changes (the box's edges on a node, the particle on a node) */
static void gimp_forms(void) {
  static const double lps[] = {0.01, 0.05, 0.125, 0.25, 1.0 / 3.0, 0.49, 0.5};
  unsigned seed = 11u;
  double worst_w = 0, worst_dw = 0, worst_q = 0, lowest = 1;
  for (size_t l = 0; l < sizeof lps / sizeof lps[0]; l++) {
    const double lp = lps[l];
    for (int i = 0; i < 20000; i++) {
      const double n = 3 + i % 50, edge[] = {n + lp, n - lp, n, n + 1 - lp, n + rnd(&seed)};
      const double xi = edge[i % 5] + (i % 7 == 0 ? 1e-15 * (i % 2 ? 1 : -1) : 0);
      double w[3], dw[3], wp[3], dwp[3], wq[3], dwq[3];
      const int b = mrn_shape_gimp_1d(xi, lp, w, dw), bp = mrn_shape_gimp_1d_piecewise(xi, lp, wp, dwp);
      CHECK(b == bp);
      const double ulps = DBL_EPSILON * (fabs(xi) + 1); /* the error of xi - lp */
      for (int k = 0; k < 3; k++) {
        worst_w = fmax(worst_w, fabs(w[k] - wp[k]) / ulps);
        worst_dw = fmax(worst_dw, fabs(dw[k] - dwp[k]) * lp / ulps);
        lowest = fmin(lowest, w[k]);
      }
      if (lp == 0.5 && mrn_shape_quadratic_1d(xi, wq, dwq) == b)
        for (int k = 0; k < 3; k++)
          worst_q = fmax(worst_q, fmax(fabs(w[k] - wq[k]), fabs(dw[k] - dwq[k])) / (DBL_EPSILON * (fabs(xi) + 1)));
    }
  }
  printf("uGIMP 1D, factored against piecewise, in DBL_EPSILON (|xi| + 1): weights %.2f, derivatives times lp "
         "%.2f; lp = 1/2 against the quadratic B-spline %.2f; smallest weight %.1e\n", worst_w, worst_dw, worst_q,
         lowest);
  CHECK(worst_w <= 4 && worst_dw <= 4 && worst_q <= 4);
  CHECK(lowest >= 0.0);
}

int main(void) {
  gimp_forms();
  static const char *modes[] = {"extended", "truncated", "modified", "wls"};
  for (int dim = 2; dim <= 3; dim++)
    for (int shape = 0; shape < MRN_SHAPE_KIND_COUNT; shape++)
      for (int mode = 0; mode < MRN_KERNEL_BOUNDARY_COUNT && mrn_shape_takes_dim(shape, dim); mode++) {
        errors e = sweep(dim, (mrn_shape_kind)shape, (mrn_kernel_boundary)mode, 0);
        double worst = fmax(fmax(e.unity, e.linear / 0.1), fmax(e.grad_sum * 0.1, e.grad_linear));
        printf("%dD %-18s %-9s  |sum N - 1| %.1e  |sum N x - x_p|/h %.1e  |sum grad N| h %.1e  |sum x grad N - I| %.1e\n",
               dim, mrn_shape_info_of((mrn_shape_kind)shape)->name, modes[mode], e.unity, e.linear / 0.1,
               e.grad_sum * 0.1, e.grad_linear);
        if (mode == MRN_KERNEL_TRUNCATED) {
          /* linear hat functions (CPDI's grid basis, at a point) are never
           * cut by the faces; the wider ones are */
          if (mrn_shape_support((mrn_shape_kind)shape) > 2) CHECK(e.unity > 1e-3 && e.linear > 1e-4);
        } else {
          CHECK(worst < 1e-12);
        }
      }
  CHECK_DONE();
}

/* moraine: APIC's affine matrix for the multilinear kernel (affine_fit.h). */
#include "transfer/affine_fit.h"

#include <math.h>

#include "core/tensor.h"

/* the quadratic B-spline neighbourhood of x along each axis: weights, node
 * numbers (wrapped on periodic axes, -1 beyond a face) and offsets */
typedef struct fit_axes {
  double w[3][3], off[3][3];
  int node[3][3];
} fit_axes;

static void fit_axes_build(const mrn_grid *g, const mrn_kernel_options *k, int dim, const double *x, fit_axes *a) {
  for (int d = 0; d < dim; d++) {
    double dw[3];
    const int base = mrn_shape_quadratic_1d((x[d] - g->origin[d]) * g->inv_cell, a->w[d], dw);
    const int ncell = g->ncell[d];
    for (int e = 0; e < 3; e++) {
      const int n = base + e;
      a->off[d][e] = g->origin[d] + n * g->cell - x[d];
      if (k->periodic & (1u << d)) a->node[d][e] = (n % ncell + ncell) % ncell;
      else a->node[d][e] = n >= 0 && n <= ncell ? n : -1;
    }
  }
}

/* node c of the 3^d neighbourhood (x fastest): its weight W = N^q m (0 when
 * beyond a face or at or below the mass floor), index and offset */
static double fit_node(const mrn_grid *g, const fit_axes *a, int dim, double mass_floor, int c, size_t *idx,
                       double b[3]) {
  const int e[3] = {c % 3, c / 3 % 3, c / 9};
  int n[3] = {0, 0, 0};
  double N = 1.0;
  for (int d = 0; d < dim; d++) {
    n[d] = a->node[d][e[d]];
    if (n[d] < 0) return 0.0;
    N *= a->w[d][e[d]];
    b[d] = a->off[d][e[d]];
  }
  *idx = mrn_grid_index(g, n[0], n[1], n[2]);
  const double m = g->mass[*idx];
  return m > mass_floor ? N * m : 0.0;
}

void mrn_affine_fit(const mrn_grid *g, const mrn_kernel_options *k, int dim, double mass_floor, const double *x,
                    double *C) {
  fit_axes a;
  fit_axes_build(g, k, dim, x, &a);
  const int count = dim == 2 ? 9 : 27;
  double sw = 0.0, bw[3] = {0, 0, 0}, vw[3] = {0, 0, 0}, b[3] = {0, 0, 0};
  size_t idx = 0;
  for (int c = 0; c < count; c++) { /* the weighted means */
    const double W = fit_node(g, &a, dim, mass_floor, c, &idx, b);
    sw += W;
    for (int d = 0; d < dim; d++) bw[d] += W * b[d], vw[d] += W * g->vel_new[3 * idx + d];
  }
  for (int e = 0; e < dim * dim; e++) C[e] = 0.0;
  if (!(sw > 0.0)) return;
  for (int d = 0; d < dim; d++) bw[d] /= sw, vw[d] /= sw;
  double M[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, R[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, Mi[9];
  for (int c = 0; c < count; c++) { /* the centred moments */
    const double W = fit_node(g, &a, dim, mass_floor, c, &idx, b);
    if (W == 0.0) continue;
    for (int r = 0; r < dim; r++)
      for (int s = 0; s < dim; s++) {
        M[3 * r + s] += W * (b[r] - bw[r]) * (b[s] - bw[s]);
        R[3 * r + s] += W * (g->vel_new[3 * idx + r] - vw[r]) * (b[s] - bw[s]);
      }
  }
  /* an axis the weighted nodes do not spread along gets no gradient; its
   * covariances with the others vanish with its variance */
  const double tiny = 1e-12 * g->cell * g->cell;
  for (int d = 0; d < 3; d++)
    if (d >= dim || !(M[4 * d] > tiny * sw)) {
      for (int e = 0; e < 3; e++) M[3 * d + e] = M[3 * e + d] = R[3 * e + d] = 0.0;
      M[4 * d] = 1.0;
    }
  if (mat_inverse(M, Mi)) return;
  for (int r = 0; r < dim; r++)
    for (int s = 0; s < dim; s++) {
      double v = 0.0;
      for (int e = 0; e < dim; e++) v += R[3 * r + e] * Mi[3 * e + s];
      C[dim * r + s] = v;
    }
}

/* moraine: the stencils of the reference kernels (see reference.h): a
 * tensor product of 1D rows with the face treatments and the WLS
 * correction, and the domain-tracking shapes' own (cpdi.h, cpgimp.h).
 * Each product is formed in the order of the fast kernels' general form
 * (stencil.h), as reference.c says. */
#include "transfer/reference.h"

#include <math.h>

#include "particles/domain.h"
#include "transfer/cpdi.h"
#include "transfer/cpgimp.h"
#include "transfer/wls.h"

/* ---- the stencil -------------------------------------------------------------- */

/* uGIMP's particle half-width in cells, from its initial volume; at most
 * half a cell, so that the support stays within 3 nodes */
static double gimp_half_width(const mrn_transfer *t, size_t p) {
  const double lp = mrn_particle_half_side(t->particles->vol0[p], t->dim) * t->grid->inv_cell;
  return lp > 0.5 ? 0.5 : lp;
}

/* The face treatment along one axis (mrn_kernel_boundary, shape/shape.h) of
 * the weights w and derivatives dw of nodes base .. base + sup - 1: a node
 * beyond a face is dropped (truncated, WLS) or, for the modified kernels,
 * folded onto the face node and its inner neighbour by linear extrapolation,
 * u_e = (1 + k) u_face - k u_next with k the node's distance from the face.
 * Returns 1 when the kernel reached beyond a face. */
static int face_treatment(mrn_kernel_boundary mode, int base, int sup, int ncell, double *w, double *dw) {
  int crossed = 0;
  for (int e = 0; e < sup; e++) {
    const int node = base + e;
    if (node >= 0 && node <= ncell) continue;
    if (w[e] != 0.0 || dw[e] != 0.0) crossed = 1;
    if (mode == MRN_KERNEL_MODIFIED) {
      const int face = node < 0 ? 0 : ncell, next = node < 0 ? 1 : ncell - 1;
      const double k = fabs((double)(node - face));
      w[face - base] += (1 + k) * w[e];
      dw[face - base] += (1 + k) * dw[e];
      w[next - base] -= k * w[e];
      dw[next - base] -= k * dw[e];
    }
    w[e] = dw[e] = 0.0;
  }
  return crossed;
}

/* One axis of the stencil: the 1D weights (shape.h) of the particle at x,
 * adjusted at the faces or wrapped around a periodic axis; node[] gets the
 * node numbers. Returns 1 when a face treatment cut the kernel. */
static int axis_stencil(const mrn_transfer *t, int d, double x, double lp, int *base,
                        int *node, double *w, double *dw) {
  const mrn_kernel_options *k = &t->kernel;
  const mrn_grid *g = t->grid;
  const int sup = mrn_shape_support(k->shape), ncell = g->ncell[d];
  *base = mrn_shape_weights_1d(k->shape, (x - g->origin[d]) * g->inv_cell, lp, w, dw);
  if (k->shape == MRN_SHAPE_LINEAR && *base == ncell) {
    /* on the upper face: the last cell's hat functions, gradient from inside */
    *base = ncell - 1;
    w[0] = 0.0, w[1] = 1.0;
    dw[0] = -1.0, dw[1] = 1.0;
  }
  int crossed = 0;
  if (k->periodic & (1u << d)) {
    for (int e = 0; e < sup; e++) node[e] = ((*base + e) % ncell + ncell) % ncell;
  } else {
    if (k->boundary != MRN_KERNEL_EXTENDED) crossed = face_treatment(k->boundary, *base, sup, ncell, w, dw);
    for (int e = 0; e < sup; e++) node[e] = *base + e;
  }
  return crossed;
}

/* The tensor product N_i = prod_d w_d (002, Eq. 52), its gradient
 * dN_i/dx_d = dw_d / h prod_{e != d} w_e and the branch vectors, node by
 * node with x fastest; then the WLS correction of the values where the
 * kernel was cut (002, Eqs. 58, 61) and of the gradients (002, Eq. 62) there
 * or, with the MLS gradient, everywhere (002 Remark 4). */
void mrn_ref_stencil_build(const mrn_transfer *t, size_t p, mrn_ref_stencil *s) {
  if (mrn_shape_is_cpdi(t->kernel.shape)) { /* the domain's corners (cpdi.h) */
    mrn_cpdi_stencil(t, p, s);
    return;
  }
  if (t->kernel.shape == MRN_SHAPE_CPGIMP) { /* the box sized from the domain (cpgimp.h) */
    mrn_cpgimp_stencil(t, p, s);
    return;
  }
  const mrn_kernel_options *k = &t->kernel;
  const int dim = t->dim, sup = mrn_shape_support(k->shape);
  const double *x = t->particles->x + 3 * p;
  const double lp = k->shape == MRN_SHAPE_GIMP ? gimp_half_width(t, p) : 0.0;
  double w[3][MRN_SHAPE_MAX_SUPPORT], dw[3][MRN_SHAPE_MAX_SUPPORT];
  int base[3] = {0, 0, 0}, node[3][MRN_SHAPE_MAX_SUPPORT] = {{0}}, at[3][MRN_SHAPE_MAX_SUPPORT] = {{0}}, crossed = 0;
  const int n[3] = {sup, sup, dim == 3 ? sup : 1};
  for (int d = 0; d < dim; d++) {
    crossed |= axis_stencil(t, d, x[d], lp, &base[d], node[d], w[d], dw[d]);
    for (int k = 0; k < sup; k++) at[d][k] = base[d] + k; /* unwrapped */
  }
  mrn_ref_tensor_stencil(t, p, n, MRN_SHAPE_MAX_SUPPORT, w[0], dw[0], node[0], at[0], s);
  const int correct_values = k->boundary == MRN_KERNEL_WLS && crossed;
  if (correct_values || k->mls_gradient) mrn_wls_correct(dim, s->count, s->N, s->dN, s->off, correct_values, 1);
}

void mrn_ref_tensor_stencil(const mrn_transfer *t, size_t p, const int n[3], int stride, const double *w,
                            const double *dw, const int *node, const int *at, mrn_ref_stencil *s) {
  const mrn_grid *g = t->grid;
  const int dim = t->dim;
  const double *x = t->particles->x + 3 * p;
  s->count = n[0] * n[1] * n[2];
  int c = 0; /* node by node, x fastest */
  for (int iz = 0; iz < n[2]; iz++)
    for (int iy = 0; iy < n[1]; iy++)
      for (int ix = 0; ix < n[0]; ix++, c++) {
        const int idx[3] = {ix, iy, iz};
        double N = 1.0;
        for (int d = 0; d < dim; d++) N *= w[d * stride + idx[d]];
        for (int d = 0; d < dim; d++) {
          double dN = dw[d * stride + idx[d]] * g->inv_cell;
          for (int e = 0; e < dim; e++)
            if (e != d) dN *= w[e * stride + idx[e]];
          s->dN[dim * c + d] = dN;
          s->off[dim * c + d] = g->origin[d] + at[d * stride + idx[d]] * g->cell - x[d];
        }
        s->N[c] = N;
        s->node[c] = mrn_grid_index(g, node[ix], node[stride + iy], dim == 3 ? node[2 * stride + iz] : 0);
      }
}

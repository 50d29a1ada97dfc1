/* moraine: cpGIMP (see cpgimp.h). */
#include "transfer/cpgimp.h"

#include <math.h>
#include <string.h>

#include "particles/domain.h"

/* ---- one axis ----------------------------------------------------------------- */

/* the hat function and its antiderivative Phi(s) = int_{-inf}^s N */
static double hat(double s) { return fmax(0.0, 1.0 - fabs(s)); }

static double hat_integral(double s) {
  if (s <= -1.0) return 0.0;
  if (s <= 0.0) return 0.5 * (1.0 + s) * (1.0 + s);
  if (s < 1.0) return 1.0 - 0.5 * (1.0 - s) * (1.0 - s);
  return 1.0;
}

int mrn_cpgimp_nodes(double l) { return 2 + (int)ceil(2.0 * l); }

int mrn_cpgimp_1d(double xi, double l, double *w, double *dw) {
  if (l <= 0.5) return mrn_shape_gimp_1d(xi, l, w, dw); /* uGIMP's form, 3 nodes */
  const int base = (int)floor(xi - l), n = mrn_cpgimp_nodes(l);
  const double share = 0.5 / l;
  for (int k = 0; k < n; k++) {
    const double r = xi - (base + k);
    w[k] = share * (hat_integral(r + l) - hat_integral(r - l));
    dw[k] = share * (hat(r + l) - hat(r - l));
  }
  return base;
}

/* ---- the box --------------------------------------------------------------------- */

int mrn_cpgimp_box(const double A[9], int dim, double inv_cell, double l[3]) {
  int count = 1;
  for (int d = 0; d < dim; d++) l[d] = A[4 * d] * inv_cell;
  for (int d = 0; d < dim; d++) {
    if (!(l[d] > 0.0 && l[d] <= MRN_REF_STENCIL_MAX)) return 0; /* NaN too; the bound keeps ceil in range */
    count *= mrn_cpgimp_nodes(l[d]);
  }
  return count <= MRN_REF_STENCIL_MAX ? count : 0;
}


/* ---- the stencil ------------------------------------------------------------------- */

/* a node number along d: wrapped around a periodic axis, else taken back
 * onto the last ghost layer when beyond it */
static int axis_node(const mrn_transfer *t, int d, int i) {
  const mrn_grid *g = t->grid;
  const int ncell = g->ncell[d];
  if ((t->kernel.periodic >> d) & 1u) return (i % ncell + ncell) % ncell;
  return i < -g->pad ? -g->pad : i > ncell + g->pad ? ncell + g->pad : i;
}

/* a refused box: NaN on the particle's own node, so that it shows */
static void refused(const mrn_transfer *t, size_t p, mrn_ref_stencil *s) {
  const mrn_grid *g = t->grid;
  int ijk[3] = {0, 0, 0};
  for (int d = 0; d < t->dim; d++) {
    ijk[d] = axis_node(t, d, (int)floor((t->particles->x[3 * p + d] - g->origin[d]) * g->inv_cell));
    s->dN[d] = s->off[d] = NAN;
  }
  s->count = 1;
  s->N[0] = NAN;
  s->node[0] = mrn_grid_index(g, ijk[0], ijk[1], ijk[2]);
}

/* The tensor product of the 1D weights, its gradient and the branch
 * vectors, node by node with x fastest, formed as the reference stencil
 * forms uGIMP's (reference.c) */
void mrn_cpgimp_stencil(const mrn_transfer *t, size_t p, mrn_ref_stencil *s) {
  const mrn_grid *g = t->grid;
  const int dim = t->dim;
  const double *x = t->particles->x + 3 * p;
  double A[9], l[3] = {0, 0, 0};
  mrn_particle_domain_now(t->particles, t->dim, p, t->domain, A);
  if (!mrn_cpgimp_box(A, dim, g->inv_cell, l)) {
    refused(t, p, s);
    return;
  }
  double w[3][MRN_REF_STENCIL_MAX], dw[3][MRN_REF_STENCIL_MAX];
  int n[3] = {1, 1, 1}, node[3][MRN_REF_STENCIL_MAX], at[3][MRN_REF_STENCIL_MAX]; /* rows beyond n unread */
  for (int d = 0; d < dim; d++) {
    const int base = mrn_cpgimp_1d((x[d] - g->origin[d]) * g->inv_cell, l[d], w[d], dw[d]);
    n[d] = mrn_cpgimp_nodes(l[d]);
    for (int k = 0; k < n[d]; k++) {
      node[d][k] = axis_node(t, d, base + k);
      at[d][k] = (t->kernel.periodic >> d) & 1u ? base + k : node[d][k]; /* unwrapped, or taken back */
    }
  }
  mrn_ref_tensor_stencil(t, p, n, MRN_REF_STENCIL_MAX, w[0], dw[0], node[0], at[0], s);
}

long mrn_cpgimp_domains(const mrn_particles *ps, int dim, double inv_cell, double *A, double *extent) {
  const int offset = mrn_particle_domain_offset(ps);
  double widest = 0.0;
  for (size_t p = 0; p < ps->n; p++) {
    double U0[9], l[3], *a = A + 9 * p;
    mrn_particle_domain(ps, dim, p, offset, mrn_particle_half_side(ps->vol0[p], dim), U0, a);
    if (!mrn_cpgimp_box(a, dim, inv_cell, l)) return (long)p;
    for (int d = 0; d < dim; d++) widest = fmax(widest, l[d]);
  }
  *extent = widest;
  return -1;
}

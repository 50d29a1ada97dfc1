/* moraine: initial grad v and APIC C for particles given initial velocities
 * (000 §3.2, last paragraph): repeat the Taylor transfer (000, Eqs. 19-22)
 * until the particles' grad v stops changing; APIC's C takes the same value. */
#include <math.h>
#include <string.h>

#include "core/parallel.h"
#include "core/tensor.h"
#include "transfer/kernels.h"

#define MAX_ITERATIONS 100

typedef struct taylor_ctx {
  double *affine; /* stored as the particles keep it (mrn_tensor_stride) */
  int dim;
  double change, scale; /* max |grad v - affine|, max |grad v| */
} taylor_ctx;

/* gradient sink: the new grad v of a chunk (9 values per particle)
 * replaces its affine matrices, noting how much they changed (maxima: the
 * same for any order of chunks; in 2D L has no z row or column) */
static long take_gradient(void *ctx, size_t lo, size_t hi, const double *L) {
  taylor_ctx *t = ctx;
  double change = 0.0, scale = 0.0;
  const size_t stride = (size_t)mrn_tensor_stride(t->dim);
  for (size_t i = lo; i < hi; i++) {
    double *A = t->affine + stride * i, packed[9];
    mrn_tensor_pack(t->dim, L + 9 * (i - lo), packed);
    for (size_t k = 0; k < stride; k++) {
      change = fmax(change, fabs(packed[k] - A[k]));
      scale = fmax(scale, fabs(packed[k]));
    }
    memcpy(A, packed, stride * sizeof(double));
  }
#pragma omp critical(mrn_taylor_change)
  {
    t->change = fmax(t->change, change);
    t->scale = fmax(t->scale, scale);
  }
  return -1;
}

int mrn_transfer_init_affine(mrn_transfer *tr) {
  mrn_particles *ps = tr->particles;
  mrn_grid *g = tr->grid;
  /* the same transfer with the Taylor grid velocity (000, Eqs. 19-22) */
  mrn_scheme taylor = *tr->scheme;
  taylor.grid_velocity = MRN_VGRID_TAYLOR;
  mrn_transfer t = *tr;
  t.scheme = &taylor;
  memset(ps->affine, 0, (size_t)mrn_tensor_stride(tr->dim) * ps->n * sizeof(double));
  int it;
  for (it = 1; it <= MAX_ITERATIONS; it++) {
    mrn_p2g(&t, 1, 0); /* (000, Eq. 19) with the current grad v */
    if (t.sum_nodal) {
      t.sum_nodal(t.sum_ctx, g->mass, 1);
      t.sum_nodal(t.sum_ctx, g->mom, 3);
    }
    for (size_t i = 0; i < g->n; i++)
      for (int d = 0; d < 3; d++)
        g->vel[3 * i + d] = g->mass[i] > tr->mass_floor ? g->mom[3 * i + d] / g->mass[i] : 0.0;
    taylor_ctx c = {ps->affine, tr->dim, 0.0, 0.0};
    const mrn_gradient_sink sink = {take_gradient, &c, MRN_PHASE_G2P};
    mrn_gradient(&t, g->vel, &sink); /* (000, Eq. 22) */
    if (t.max_over) { /* every process iterates as long as the slowest */
      double m[2] = {c.change, c.scale};
      t.max_over(t.sum_ctx, m, 2);
      c.change = m[0], c.scale = m[1];
    }
    if (c.change <= 1e-15 * c.scale || c.scale == 0.0) break;
  }
  tr->sort_now = t.sort_now; /* a sort done here is not done again */
  return it;
}

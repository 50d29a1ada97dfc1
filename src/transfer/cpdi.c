/* moraine: CPDI and CPDI2 (see cpdi.h, cpdi2.h). */
#include "transfer/cpdi.h"

#include <math.h>
#include <string.h>

#include "core/parallel.h"
#include "core/tensor.h"
#include "grid/active.h"
#include "particles/domain.h"
#include "transfer/cpdi2.h"

/* ---- the stencil ---------------------------------------------------------------- */

/* The hat functions along axis d at a corner with grid coordinate xi: the
 * first node (unwrapped) into *base, the node numbers into node[2], the
 * weights into w[2]. Off a periodic axis a corner beyond the ghost layers
 * is taken back onto the last of them. */
static void corner_axis(const mrn_transfer *t, int d, double xi, int *base, int node[2], double w[2]) {
  const mrn_grid *g = t->grid;
  const int ncell = g->ncell[d];
  const int periodic = (t->kernel.periodic >> d) & 1u;
  if (!periodic) xi = fmin(fmax(xi, -g->pad), ncell + g->pad);
  double dw[2];
  *base = mrn_shape_linear_1d(xi, w, dw);
  if (!periodic && *base == ncell + g->pad) (*base)--, w[0] = 0.0, w[1] = 1.0;
  for (int e = 0; e < 2; e++)
    node[e] = periodic ? ((*base + e) % ncell + ncell) % ncell : *base + e;
}

/* One corner x_c's entries, its 2^d nodes with x fastest: the hat
 * functions N_i(x_c) times `share` (the weights) and times `gshare` grad
 * (the gradients); x the particle's centre, for the branch vectors */
static void corner_entries(const mrn_transfer *t, const double *x, const double xc[3], double share, double gshare,
                           const double grad[3], mrn_ref_stencil *s) {
  const mrn_grid *g = t->grid;
  const int dim = t->dim;
  double w[3][2] = {{1, 1}, {1, 1}, {1, 1}};
  int base[3] = {0, 0, 0}, node[3][2] = {{0, 0}, {0, 0}, {0, 0}};
  for (int a = 0; a < dim; a++) corner_axis(t, a, (xc[a] - g->origin[a]) * g->inv_cell, &base[a], node[a], w[a]);
  for (int n = 0; n < (1 << dim); n++) {
    const int idx[3] = {n & 1, (n >> 1) & 1, (n >> 2) & 1};
    double N = share, G = gshare;
    for (int d = 0; d < dim; d++) N *= w[d][idx[d]], G *= w[d][idx[d]];
    const int at = s->count++;
    for (int d = 0; d < dim; d++) {
      s->dN[dim * at + d] = G * grad[d];
      s->off[dim * at + d] = g->origin[d] + (base[d] + idx[d]) * g->cell - x[d];
    }
    s->N[at] = N;
    s->node[at] = mrn_grid_index(g, node[0][idx[0]], node[1][idx[1]], dim == 3 ? node[2][idx[2]] : 0);
  }
}

/* CPDI1: S_ip = (1/2^d) sum_c N_i(x_c), grad S_ip = (1/2^d) sum_c N_i(x_c)
 * J^-T xi_c (cpdi.h), corner by corner */
static void parallelogram(const mrn_transfer *t, size_t p, mrn_ref_stencil *s) {
  const int dim = t->dim, corners = 1 << dim;
  const double *x = t->particles->x + 3 * p, share = 1.0 / corners;
  double A[9], Ji[9];
  mrn_particle_domain_now(t->particles, t->dim, p, t->domain, A);
  if (dim == 2) A[8] = 1.0; /* the plane block's inverse */
  if (mat_inverse(A, Ji))
    for (int e = 0; e < 9; e++) Ji[e] = NAN;
  for (int c = 0; c < corners; c++) {
    double xi_c[3], xc[3] = {0, 0, 0}, grad[3] = {0, 0, 0};
    for (int k = 0; k < dim; k++) xi_c[k] = (c >> k) & 1 ? 1.0 : -1.0;
    for (int a = 0; a < dim; a++) {
      xc[a] = x[a]; /* the corner x_p + sum_k xi_ck r_k, r_k the columns of A */
      for (int k = 0; k < dim; k++) xc[a] += xi_c[k] * A[3 * a + k];
      for (int k = 0; k < dim; k++) grad[a] += Ji[3 * k + a] * xi_c[k]; /* (J^-T xi_c)_a */
    }
    corner_entries(t, x, xc, share, share, grad, s);
  }
}

/* CPDI2: S_ip = (1/V_p) sum_c N_i(x_c) w_c, grad S_ip = (1/V_p) sum_c
 * N_i(x_c) g_c (cpdi2.h), over the corners the step froze or, outside a
 * step, the stored ones; the integrals from the offsets about x_p, which
 * they do not depend on, for the round-off */
static void quadrilateral(const mrn_transfer *t, size_t p, mrn_ref_stencil *s) {
  const double *x = t->particles->x + 3 * p;
  double q[4][2], w[4], gc[4][2];
  if (t->domain)
    for (int c = 0; c < 4; c++)
      for (int a = 0; a < 2; a++) q[c][a] = t->domain[8 * p + 2 * c + a] - x[a];
  else
    mrn_cpdi2_offsets(t->particles, p, q);
  const double V = mrn_cpdi2_integrals(q, w, gc), inv = V > 0.0 ? 1.0 / V : NAN; /* an inverted domain: NaN */
  for (int c = 0; c < 4; c++) {
    const double xc[3] = {x[0] + q[c][0], x[1] + q[c][1], 0.0}, grad[3] = {gc[c][0], gc[c][1], 0.0};
    corner_entries(t, x, xc, w[c] * inv, inv, grad, s);
  }
}

/* CPDI's stencil: 2^d corners x 2^d nodes, a node reached from several
 * corners listed once per corner */
void mrn_cpdi_stencil(const mrn_transfer *t, size_t p, mrn_ref_stencil *s) {
  s->count = 0;
  if (t->kernel.shape == MRN_SHAPE_CPDI2) quadrilateral(t, p, s);
  else parallelogram(t, p, s);
}

void mrn_cpdi_point_velocity(const mrn_transfer *t, const double xc[3], const double *gvel, double v[3]) {
  static const double no_gradient[3] = {0, 0, 0};
  mrn_ref_stencil s;
  s.count = 0;
  corner_entries(t, xc, xc, 1.0, 0.0, no_gradient, &s); /* the hat functions at xc alone */
  for (int d = 0; d < 3; d++) v[d] = 0.0;
  for (int k = 0; k < s.count; k++)
    for (int d = 0; d < t->dim; d++) v[d] += s.N[k] * gvel[3 * s.node[k] + d];
}

double mrn_cpdi_gradient_bound(const mrn_transfer *t, size_t p) {
  const int dim = t->dim;
  mrn_ref_stencil s;
  mrn_cpdi_stencil(t, p, &s);
  double worst = 0.0;
  for (int k = 0; k < s.count; k++) {
    int first = 1; /* a node's parts summed at its first entry */
    for (int j = 0; j < k && first; j++) first = s.node[j] != s.node[k];
    if (!first) continue;
    double g[3] = {0, 0, 0}, n2 = 0.0;
    for (int j = k; j < s.count; j++)
      if (s.node[j] == s.node[k])
        for (int d = 0; d < dim; d++) g[d] += s.dN[dim * j + d];
    for (int d = 0; d < dim; d++) n2 += g[d] * g[d];
    worst = fmax(worst, sqrt(n2));
  }
  return worst;
}

double mrn_cpdi_domains(const mrn_particles *ps, int dim, double inv_cell, double *A) {
  const int offset = mrn_particle_domain_offset(ps);
  double reach = 0.0;
  for (size_t p = 0; p < ps->n; p++) {
    double U0[9], *a = A + 9 * p;
    mrn_particle_domain(ps, dim, p, offset, mrn_particle_half_side(ps->vol0[p], dim), U0, a);
    for (int d = 0; d < dim; d++) {
      double r = 0.0; /* the corners' largest distance from x_p along d */
      for (int k = 0; k < dim; k++) r += fabs(a[3 * d + k]);
      reach = fmax(reach, r * inv_cell);
    }
  }
  return reach;
}

/* ---- the kernels ------------------------------------------------------------------ */

void mrn_cpdi_p2g(mrn_transfer *tr, int momentum, int force) {
  const double t0 = mrn_phase_begin();
  if (!momentum && !force) return;
  mrn_grid *g = tr->grid;
  tr->sort_now = 0; /* no binning, so no reordering by block */
  mrn_grid_active_all(g); /* a domain may reach any node */
  mrn_grid_active_switch(g, (momentum ? MRN_CLEAR_MASS_MOM : 0u) | (force ? MRN_CLEAR_FORCE : 0u));
  mrn_ref_stencil s;
  for (size_t p = 0; p < tr->particles->n; p++) { /* index order, one thread: any node from any particle */
    mrn_ref_stencil_build(tr, p, &s);
    mrn_ref_p2g_add(tr, p, &s, momentum, force);
  }
  mrn_phase_end(MRN_PHASE_P2G, t0);
}

/* Particles [lo, hi): with `move` G2P (after the gradient from V~ when
 * there is a sink: G2P may move them), else the gradients from gvel; the
 * gradients to the sink, then the chunk to `after` */
static void chunk(mrn_transfer *tr, long lo, long hi, int move, double dt, double *dx, const double *gvel,
                  const mrn_gradient_sink *sink, const mrn_particle_pass *after, long bad[2], double *spent) {
  double L[9 * MRN_GRADIENT_CHUNK];
  mrn_ref_stencil s;
  for (long p = lo; p < hi; p++) {
    if (sink) {
      mrn_ref_stencil_build(tr, (size_t)p, &s);
      mrn_ref_gradient(tr, &s, gvel, L + 9 * (p - lo));
    }
    if (move) mrn_ref_g2p_one(tr, (size_t)p, dt, dx, NULL);
  }
  if (sink) {
    const double t0 = mrn_phase_begin();
    const long b = sink->chunk(sink->ctx, (size_t)lo, (size_t)hi, L);
    if (mrn_profile_seconds) *spent += mrn_profile_now() - t0;
    if (b >= 0 && (bad[0] < 0 || b < bad[0])) bad[0] = b;
  }
  if (after) {
    const long b = after->chunk(after->ctx, (size_t)lo, (size_t)hi);
    if (b >= 0 && (bad[1] < 0 || b < bad[1])) bad[1] = b;
  }
}

/* every particle in chunks of MRN_GRADIENT_CHUNK, chunks in parallel; the
 * lowest index the sink rejected, or -1 (the after pass's in *after_bad) */
static long chunks(mrn_transfer *tr, int move, double dt, double *dx, const double *gvel,
                   const mrn_gradient_sink *sink, const mrn_particle_pass *after, long *after_bad) {
  const double t0 = mrn_phase_begin();
  const long n = (long)tr->particles->n, nchunks = (n + MRN_GRADIENT_CHUNK - 1) / MRN_GRADIENT_CHUNK;
  long first = n, first_after = n;
  double spent = 0.0;
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS) reduction(min : first, first_after) \
    reduction(+ : spent)
  for (long c = 0; c < nchunks; c++) {
    const long lo = c * MRN_GRADIENT_CHUNK, hi = lo + MRN_GRADIENT_CHUNK < n ? lo + MRN_GRADIENT_CHUNK : n;
    long bad[2] = {-1, -1};
    chunk(tr, lo, hi, move, dt, dx, gvel, sink, after, bad, &spent);
    if (bad[0] >= 0 && bad[0] < first) first = bad[0];
    if (bad[1] >= 0 && bad[1] < first_after) first_after = bad[1];
  }
  mrn_phase_end_split(MRN_PHASE_G2P, sink ? sink->phase : MRN_PHASE_G2P, t0, spent, n > MRN_OMP_MIN_ITEMS);
  if (after_bad) *after_bad = first_after < n ? first_after : -1;
  return first < n ? first : -1;
}

long mrn_cpdi_g2p_then(mrn_transfer *tr, double dt, double *dx, const mrn_gradient_sink *sink,
                       const mrn_particle_pass *after, long *after_bad) {
  return chunks(tr, 1, dt, dx, tr->grid->vel_new, sink, after, after_bad);
}

long mrn_cpdi_gradient(mrn_transfer *tr, const double *gvel, const mrn_gradient_sink *sink) {
  return chunks(tr, 0, 0.0, NULL, gvel, sink, NULL, NULL);
}

void mrn_cpdi_grid_to_particles(mrn_transfer *tr, const double *gvel, double *pvel) {
  const int dim = tr->dim;
  const long n = (long)tr->particles->n;
#pragma omp parallel for schedule(static) if (n > MRN_OMP_MIN_ITEMS)
  for (long p = 0; p < n; p++) {
    mrn_ref_stencil s;
    mrn_ref_stencil_build(tr, (size_t)p, &s);
    double v[3] = {0, 0, 0};
    for (int c = 0; c < s.count; c++)
      for (int d = 0; d < dim; d++) v[d] += s.N[c] * gvel[3 * s.node[c] + d];
    for (int d = 0; d < 3; d++) pvel[3 * p + d] = v[d];
  }
}

void mrn_cpdi_particles_to_grid(mrn_transfer *tr, const double *pvel, double *gvel) {
  const mrn_grid *g = tr->grid;
  const mrn_particles *ps = tr->particles;
  const int dim = tr->dim;
  memset(gvel, 0, 3 * g->n * sizeof(double));
  mrn_ref_stencil s;
  for (size_t p = 0; p < ps->n; p++) {
    mrn_ref_stencil_build(tr, p, &s);
    for (int c = 0; c < s.count; c++)
      for (int d = 0; d < dim; d++) gvel[3 * s.node[c] + d] += s.N[c] * ps->mass[p] * pvel[3 * p + d];
  }
  for (size_t i = 0; i < g->n; i++)
    for (int d = 0; d < 3; d++) gvel[3 * i + d] = g->mass[i] > tr->mass_floor ? gvel[3 * i + d] / g->mass[i] : 0.0;
}

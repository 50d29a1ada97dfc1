/* moraine: the fast transfer kernels (transfer/kernels.h) against their
 * reference form (transfer/reference.h), in 2D and 3D, for every shape
 * function x face treatment, alone, with the MLS gradient and with a
 * periodic x axis, and every scheme: grid velocity plain / affine / Taylor
 * x velocity update PIC / FLIP / blend / XPIC(1) / XPIC(3) x position
 * update grid / particle / XPIC. Kernels: P2G (mass and momentum, with the
 * affine term or not; force; both), G2P moving the particles or storing the
 * increments, with the velocity gradients handed on or not, the gradient
 * pass, and USF's pass that hands on the gradients and scatters the force.
 * Random velocities, affine matrices, stresses and F, in two particle sets:
 * `sparse`, one particle per 5 cells along each axis (no node hears from two
 * particles), on, a hair from and away from the faces, cell edges and cell
 * centres; `dense`, 80 particles in one cell (longer than a batch of the
 * fast P2G), then runs of four in one cell, a third of them next to a face.
 *
 * What must agree, and how closely:
 * - Values of the general stencil: G2P results (v, x or dx, affine matrix,
 *   grad v) of a particle the fast kernels handle with the general stencil
 *   (MLS gradient, periodic axes, XPIC's G2P, uGIMP's G2P with APIC, and a
 *   kernel cut by a truncated, modified or WLS face), and P2G values at a
 *   node only such a particle reaches. Both forms form the same
 *   products in the same order: bitwise equal when the build rounds every
 *   operation (-ffp-contract=off). With GCC's default -ffp-contract=fast the
 *   compiler fuses a * b + c into one FMA in some sums of one form and not
 *   of the other (the general G2P gathers, for one): then within FUSED_ULP.
 * - Values of the fast stencils (linear, quadratic or cubic B-spline, uGIMP;
 *   kernel not cut): formed factor by factor (w_x w_y w_z apart, rows of nodes as
 *   vectors), the cubic weights from a factored formula, APIC's D the exact
 *   h^2/4 I or h^2/3 I instead of the sum; every nodal sum of more than one
 *   particle in block order (in 2D a run of particles with the same first
 *   node summed before it is added), not in index order. Within BOUND_ULP.
 * A bound is in units of DBL_EPSILON times the sum of the magnitudes of the
 * value's terms with each weight N replaced by 1 (a weight is computed to
 * round-off of 1, not of itself: the reference's cubic (2 - |r|)^3 / 6
 * loses the tail weights that the factored form keeps) and each gradient
 * dN by |dN| + 1/h: for a node, sum m, sum m (|v| + |A| |x_i - x_p|) and sum
 * V |sigma| (|dN| + 1/h) over the particles whose stencils reach it; for a
 * particle, |v| + sum (|V~| + |V| + |V*|) for v, dt times that for dx, plus
 * |x| for a moved x, sum |V~| (|dN| + 1/h) for grad v and TPIC's matrix,
 * sum |V~| |x_i - x_p| / D for APIC's C. */
#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "solver/simulation.h"
#include "transfer/kernels.h"
#include "transfer/reference.h"
#include "transfer/xpic.h"

#define BOUND_ULP 64.0
#define FUSED_ULP 2.0

static uint64_t rng_state;
static double rnd(void) { /* splitmix64, 53 bits in [0, 1) */
  uint64_t z = (rng_state += 0x9e3779b97f4a7c15u);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
  return (double)((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

enum { EXTRA_NONE, EXTRA_MLS, EXTRA_PERIODIC, EXTRA_COUNT };
static const char *const extra_names[] = {"", "+mls", "+periodic-x"};

/* What was compared: values both forms make of the same products in the
 * same order (`same`: bitwise, or within FUSED_ULP when the build fuses
 * multiply-adds) and the others (within BOUND_ULP), with the worst
 * differences in units of DBL_EPSILON times the scale. */
typedef struct tally {
  long general, bitwise, fast, failures;
  double worst_general, worst_fast;
} tally;

static const char *where_ = ""; /* the case, for the failure messages */
static int fused_;              /* the build fuses a * b + c (fuses_multiply_add) */

/* Whether this build rounds a * b + c once (GCC's default -ffp-contract=fast
 * on a machine with FMA): the engine is built with the same flags */
static int fuses_multiply_add(void) {
  volatile double a = 1.0 + 0x1p-30, b = 1.0 - 0x1p-30, c = -1.0;
  const double x = a, y = b, z = c;
  return x * y + z != 0.0; /* unfused: 1 - 2^-60 rounds to 1 */
}

static void compare(tally *t, const char *what, long i, double fast, double ref, double scale, int general) {
  const int same = fast == ref || (isnan(fast) && isnan(ref));
  const double ulps = same ? 0.0 : fabs(fast - ref) / (DBL_EPSILON * scale);
  double *worst = general ? &t->worst_general : &t->worst_fast;
  const double bound = general ? (fused_ ? FUSED_ULP : 0.0) : BOUND_ULP;
  if (general) t->general++, t->bitwise += same;
  else t->fast++;
  if (ulps > *worst) *worst = ulps;
  if (same || ulps <= bound) return;
  if (t->failures++ < 5)
    fprintf(stderr, "%s: %s[%ld] fast %.17g reference %.17g (%.3g ulp of %.3g, bound %g)\n", where_, what, i, fast,
            ref, ulps, scale, bound);
  check_failures++;
}

/* ---- the particles ----------------------------------------------------------------- */

/* a coordinate (in cells) within cell c of an axis of n cells: on, a hair
 * from or away from the cell's edges and centre (the quadratic B-spline's
 * stencil moves at the centre) */
static double special_coordinate(int c, int n) {
  static const double frac[] = {0.0, 1e-12, 0.5, 0.5 - 1e-13, 0.5 + 1e-13, 1.0 - 1e-12, -1.0, -1.0, -1.0};
  double f = frac[(int)(rnd() * 9)];
  if (f < 0.0) f = rnd();
  if (c == n - 1 && rnd() < 0.3) f = 1.0; /* on the upper face */
  return c + f;
}

static void set_particle_state(mrn_sim *sim, long p) {
  mrn_particles *ps = &sim->particles;
  const int dim = sim->dim, ts = dim * dim;
  for (int d = 0; d < dim; d++) ps->v[3 * p + d] = 2.0 * rnd() - 1.0;
  for (int e = 0; e < ts; e++) ps->affine[ts * p + e] = 10.0 * (rnd() - 0.5);
  for (int a = 0; a < dim; a++)
    for (int b = 0; b < dim; b++) ps->F[ts * p + dim * a + b] = (a == b) + 0.1 * (rnd() - 0.5);
  for (int e = 0; e < 6; e++) ps->stress[6 * p + e] = 2e3 * (rnd() - 0.5);
}

static void add_particle(mrn_sim *sim, const double xi[3]) {
  const mrn_grid *g = &sim->grid;
  double x[3] = {0, 0, 0};
  for (int d = 0; d < sim->dim; d++) x[d] = g->origin[d] + xi[d] * g->cell;
  const double side = (0.3 + 0.4 * rnd()) * g->cell, vol = sim->dim == 2 ? side * side : side * side * side;
  const long p = mrn_particles_add(&sim->particles, x, (0.5 + rnd()) * 1e3 * vol, vol, 0);
  CHECK(p >= 0);
  set_particle_state(sim, p);
}

/* one particle in each slot of cells 0, 5, 10, 15 along every axis */
static void seed_sparse(mrn_sim *sim) {
  const int n = sim->grid.ncell[0], dim = sim->dim;
  for (int s = 0; s < (dim == 2 ? 16 : 64); s++) {
    const int slot[3] = {s % 4, s / 4 % 4, s / 16};
    double xi[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) xi[d] = special_coordinate(5 * slot[d], n);
    add_particle(sim, xi);
  }
}

/* runs of four particles in one cell, a third of them next to a face,
 * after a run of 80 in one cell (more than a batch of the fast P2G) */
static void seed_dense(mrn_sim *sim, int runs) {
  const int n = sim->grid.ncell[0], dim = sim->dim;
  for (int k = 0; k < 80; k++) {
    double xi[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) xi[d] = 7 + rnd();
    add_particle(sim, xi);
  }
  for (int r = 0; r < runs; r++) {
    int cell[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) cell[d] = (int)(rnd() * n);
    if (r % 3 == 0) cell[(int)(rnd() * dim)] = rnd() < 0.5 ? 0 : n - 1;
    for (int k = 0; k < 4; k++) {
      double xi[3] = {0, 0, 0};
      for (int d = 0; d < dim; d++) xi[d] = k == 0 ? special_coordinate(cell[d], n) : cell[d] + rnd();
      add_particle(sim, xi);
    }
  }
}

static mrn_sim *make_sim(int dim, mrn_shape_kind shape, mrn_kernel_boundary face, int extra, int dense) {
  mrn_sim_config cfg = {.dim = dim, .origin = {-0.3, 0.7, 1.1}, .size = {1.6, 1.6, 1.6}, .cell = 0.1,
                        .shape = shape, .kernel_boundary = face};
  mrn_sim *sim = mrn_sim_new(&cfg);
  CHECK(sim != NULL);
  if (extra == EXTRA_PERIODIC) sim->boundary.face[MRN_FACE_XMIN].kind = sim->boundary.face[MRN_FACE_XMAX].kind =
                                   MRN_BC_PERIODIC;
  if (dense) seed_dense(sim, dim == 2 ? 60 : 24);
  else seed_sparse(sim);
  mrn_sim_particles_changed(sim);
  return sim;
}

/* ---- what the comparisons need ------------------------------------------------------ */

typedef struct kase {
  mrn_sim *sim;
  mrn_transfer t;   /* the simulation's transfer context, which the reference reads */
  mrn_grid ref;     /* the reference's P2G output */
  unsigned char *general; /* per particle: handled with the general stencil by the fast kernels */
  double *saved;    /* x, v, affine of every particle before G2P */
} kase;

/* every shape has a fast stencil */
static int fast_config(const mrn_kernel_options *ko) { return !ko->periodic && !ko->mls_gradient; }

/* whether the fast kernels take the general stencil for particle p: the
 * options have no fast form, or a face treatment cuts its kernel */
static int takes_general(const kase *k, size_t p) {
  if (!fast_config(&k->t.kernel)) return 1;
  if (k->t.kernel.boundary == MRN_KERNEL_EXTENDED) return 0;
  mrn_ref_stencil s;
  mrn_ref_stencil_build(&k->t, p, &s);
  for (int c = 0; c < s.count; c++) {
    int ijk[3];
    mrn_grid_node_ijk(&k->sim->grid, s.node[c], ijk);
    for (int d = 0; d < k->sim->dim; d++)
      if (ijk[d] < 0 || ijk[d] > k->sim->grid.ncell[d]) return 1;
  }
  return 0;
}

static void kase_refresh(kase *k) {
  k->t = mrn_sim_transfer(k->sim);
  for (size_t p = 0; p < k->sim->particles.n; p++) k->general[p] = takes_general(k, p);
}

static void kase_init(kase *k, mrn_sim *sim) {
  k->sim = sim;
  mrn_grid_init(&k->ref, sim->dim, sim->grid.origin, sim->grid.size, sim->grid.cell);
  k->general = malloc(sim->particles.n);
  k->saved = malloc(sim->particles.n * 15 * sizeof(double));
}

static void kase_free(kase *k) {
  mrn_grid_free(&k->ref);
  free(k->general);
  free(k->saved);
  mrn_sim_free(k->sim);
}

/* the particle fields G2P writes, saved and put back */
static void particles_save(kase *k, int restore) {
  mrn_particles *ps = &k->sim->particles;
  const size_t n = ps->n, ts = (size_t)(k->sim->dim * k->sim->dim);
  double *fields[3] = {ps->x, ps->v, ps->affine};
  const size_t len[3] = {3 * n, 3 * n, ts * n};
  double *s = k->saved;
  for (int f = 0; f < 3; f++) {
    if (restore) memcpy(fields[f], s, len[f] * sizeof(double));
    else memcpy(s, fields[f], len[f] * sizeof(double));
    s += len[f];
  }
}

/* ---- P2G ---------------------------------------------------------------------------- */

/* Per node: the sum of the magnitudes of its terms (with N <= 1: a weight
 * is exact to round-off of 1, not of itself), how many particles reach it
 * and whether all of them take the general stencil. A particle right on a
 * cell edge (a cell centre for the quadratic B-spline) may start its
 * stencil one node further in one form than in the other, reaching a node
 * with a weight of round-off size: its largest terms count at the nodes
 * next to its stencil too (`near`). 7 values per node: mass, momentum and
 * force. */
typedef struct node_scales {
  double *sum, *near;
  int *count;
  unsigned char *general, *near_fast;
} node_scales;

static void term_scales(const kase *k, size_t p, const mrn_ref_stencil *s, int c, double out[7]) {
  const mrn_particles *ps = &k->sim->particles;
  const int dim = k->sim->dim, affine = k->sim->scheme.grid_velocity != MRN_VGRID_PLAIN;
  const double m = ps->mass[p], vol = mrn_particle_volume_dim(ps, p, dim), inv_h = k->sim->grid.inv_cell;
  const double *v = ps->v + 3 * p, *A = ps->affine + (size_t)(dim * dim) * p, *sig = ps->stress + 6 * p;
  memset(out, 0, 7 * sizeof(double));
  out[0] = m;
  for (int a = 0; a < dim; a++) {
    double va = fabs(v[a]);
    for (int b = 0; affine && b < dim; b++) va += fabs(A[dim * a + b] * s->off[dim * c + b]);
    out[1 + a] = m * va;
    for (int b = 0; b < dim; b++) out[4 + a] += vol * fabs(sig[sym_index(a, b)]) * (fabs(s->dN[dim * c + b]) + inv_h);
  }
}

/* the largest terms of a fast particle into its stencil grown by one node
 * along each axis: `first` is the stencil's first node, `sup` its width */
static void spread_near(const kase *k, size_t first, int sup, const double top[7], node_scales *ns) {
  const mrn_grid *g = &k->sim->grid;
  const int w = sup + 2;
  int ijk[3];
  mrn_grid_node_ijk(g, first, ijk);
  for (int e = 0; e < (g->dim == 2 ? w * w : w * w * w); e++) {
    const int o[3] = {e % w - 1, e / w % w - 1, g->dim == 3 ? e / (w * w) - 1 : 0};
    int inside = 1;
    for (int d = 0; d < g->dim; d++) inside &= ijk[d] + o[d] >= -g->pad && ijk[d] + o[d] <= g->ncell[d] + g->pad;
    if (!inside) continue;
    const size_t j = mrn_grid_index(g, ijk[0] + o[0], ijk[1] + o[1], ijk[2] + o[2]);
    for (int q = 0; q < 7; q++) ns->near[7 * j + q] = fmax(ns->near[7 * j + q], top[q]);
    ns->near_fast[j] = 1;
  }
}

static void node_scales_fill(const kase *k, node_scales *ns) {
  const size_t n = k->sim->grid.n;
  memset(ns->sum, 0, 7 * n * sizeof(double));
  memset(ns->near, 0, 7 * n * sizeof(double));
  memset(ns->count, 0, n * sizeof(int));
  memset(ns->general, 1, n);
  memset(ns->near_fast, 0, n);
  mrn_ref_stencil s;
  for (size_t p = 0; p < k->sim->particles.n; p++) {
    mrn_ref_stencil_build(&k->t, p, &s);
    double top[7] = {0}, t[7];
    for (int c = 0; c < s.count; c++) {
      const size_t i = s.node[c];
      ns->count[i]++;
      if (!k->general[p]) ns->general[i] = 0;
      term_scales(k, p, &s, c, t);
      for (int q = 0; q < 7; q++) ns->sum[7 * i + q] += t[q], top[q] = fmax(top[q], t[q]);
    }
    if (!k->general[p]) spread_near(k, s.node[0], mrn_shape_support(k->t.kernel.shape), top, ns);
  }
}

/* the sim's grid (fast kernels) against k->ref (reference) */
static void p2g_compare(const kase *k, tally *t, int momentum, int force) {
  const mrn_grid *g = &k->sim->grid, *r = &k->ref;
  node_scales ns = {malloc(7 * g->n * sizeof(double)), malloc(7 * g->n * sizeof(double)), malloc(g->n * sizeof(int)),
                    malloc(g->n), malloc(g->n)};
  node_scales_fill(k, &ns);
  for (size_t i = 0; i < g->n; i++) {
    const int general = ns.count[i] <= 1 && ns.general[i] && !ns.near_fast[i];
    double sc[7];
    for (int q = 0; q < 7; q++) sc[q] = fmax(ns.sum[7 * i + q], ns.near[7 * i + q]);
    if (momentum) compare(t, "mass", (long)i, g->mass[i], r->mass[i], sc[0], general);
    for (int d = 0; d < k->sim->dim; d++) {
      const long id = (long)(3 * i) + d;
      if (momentum) compare(t, "momentum", id, g->mom[3 * i + d], r->mom[3 * i + d], sc[1 + d], general);
      if (force) compare(t, "force", id, g->force[3 * i + d], r->force[3 * i + d], sc[4 + d], general);
    }
  }
  free(ns.sum), free(ns.near), free(ns.count), free(ns.general), free(ns.near_fast);
}

static void check_p2g(kase *k, tally *t) {
  static const int flags[3][2] = {{1, 0}, {0, 1}, {1, 1}};
  mrn_transfer tr = k->t;
  tr.grid = &k->ref;
  for (int f = 0; f < 3; f++) {
    mrn_p2g(&k->t, flags[f][0], flags[f][1]);
    mrn_ref_p2g(&tr, flags[f][0], flags[f][1]);
    p2g_compare(k, t, flags[f][0], flags[f][1]);
  }
}

/* ---- G2P ---------------------------------------------------------------------------- */

static const double DT = 1e-3;

/* The grid velocities G2P reads: the reference's P2G and grid update
 * (with gravity) copied to the simulation's grid, and XPIC's V* from them. */
static void grid_state(kase *k) {
  mrn_sim *sim = k->sim;
  const double gravity[3] = {0.0, sim->dim == 2 ? -9.81 : 0.0, sim->dim == 3 ? -9.81 : 0.0};
  mrn_transfer tr = k->t;
  tr.grid = &k->ref;
  mrn_p2g(&k->t, 1, 1); /* the active spans of the simulation's grid */
  mrn_ref_p2g(&tr, 1, 1);
  mrn_ref_grid_update(&tr, DT, gravity);
  const size_t n = sim->grid.n;
  memcpy(sim->grid.mass, k->ref.mass, n * sizeof(double));
  memcpy(sim->grid.mom, k->ref.mom, 3 * n * sizeof(double));
  memcpy(sim->grid.force, k->ref.force, 3 * n * sizeof(double));
  memcpy(sim->grid.vel, k->ref.vel, 3 * n * sizeof(double));
  memcpy(sim->grid.vel_new, k->ref.vel_new, 3 * n * sizeof(double));
  if (sim->scheme.velocity_update == MRN_VUPDATE_XPIC) {
    double *scratch = malloc(3 * sim->particles.n * sizeof(double));
    mrn_xpic_smooth(&k->t, scratch);
    free(scratch);
  }
}

static long capture(void *ctx, size_t lo, size_t hi, const double *L) {
  memcpy((double *)ctx + 9 * lo, L, 9 * (hi - lo) * sizeof(double));
  return -1;
}

/* particle p's magnitudes: of v's terms, of B's (over D) and of L's */
typedef struct particle_scales {
  double v[3], C[3], L[3][3];
} particle_scales;

static void particle_scales_fill(const kase *k, size_t p, particle_scales *q) {
  const mrn_grid *g = &k->sim->grid;
  const int dim = k->sim->dim, xpic = k->sim->scheme.velocity_update == MRN_VUPDATE_XPIC;
  const double dinv = (k->t.kernel.shape == MRN_SHAPE_CUBIC_BSPLINE ? 3.0 : 4.0) * g->inv_cell * g->inv_cell;
  mrn_ref_stencil s;
  mrn_ref_stencil_build(&k->t, p, &s);
  memset(q, 0, sizeof *q);
  for (int a = 0; a < dim; a++) q->v[a] = fabs(k->saved[3 * k->sim->particles.n + 3 * p + a]);
  for (int c = 0; c < s.count; c++) {
    const double *Vn = g->vel_new + 3 * s.node[c], *V = g->vel + 3 * s.node[c], *Vs = g->vel_star + 3 * s.node[c];
    double offs = 0.0;
    for (int b = 0; b < dim; b++) offs += fabs(s.off[dim * c + b]);
    for (int a = 0; a < dim; a++) {
      q->v[a] += fabs(Vn[a]) + fabs(V[a]) + (xpic ? fabs(Vs[a]) : 0.0); /* N <= 1 */
      q->C[a] += fabs(Vn[a]) * offs * dinv;
      for (int b = 0; b < dim; b++) q->L[a][b] += fabs(Vn[a]) * (fabs(s.dN[dim * c + b]) + g->inv_cell);
    }
  }
}

/* the fast G2P's results (x, v, affine, dx, L) against the particles' state
 * after the reference G2P */
typedef struct g2p_out {
  double *x, *v, *affine, *dx, *L;
} g2p_out;

static void g2p_compare(const kase *k, tally *t, const g2p_out *f, const g2p_out *r, int use_dx, int use_L) {
  const mrn_particles *ps = &k->sim->particles;
  const int dim = k->sim->dim, gv = k->sim->scheme.grid_velocity;
  particle_scales q;
  for (size_t p = 0; p < ps->n; p++) {
    const int exact = k->general[p];
    const long i = (long)p;
    particle_scales_fill(k, p, &q);
    for (int a = 0; a < dim; a++) {
      compare(t, "v", i, f->v[3 * p + a], r->v[3 * p + a], q.v[a], exact);
      if (use_dx) compare(t, "dx", i, f->dx[3 * p + a], r->dx[3 * p + a], DT * q.v[a], exact);
      else compare(t, "x", i, f->x[3 * p + a], r->x[3 * p + a], fabs(r->x[3 * p + a]) + DT * q.v[a], exact);
      for (int b = 0; b < dim; b++) {
        const size_t e = (size_t)(dim * dim) * p + (size_t)(dim * a + b);
        if (gv != MRN_VGRID_PLAIN)
          compare(t, "affine", i, f->affine[e], r->affine[e], gv == MRN_VGRID_TAYLOR ? q.L[a][b] : q.C[a], exact);
        if (use_L) compare(t, "grad v", i, f->L[9 * p + 3 * a + b], r->L[9 * p + 3 * a + b], q.L[a][b], exact);
      }
    }
  }
}

static g2p_out g2p_out_new(size_t n) {
  g2p_out o = {malloc(3 * n * sizeof(double)), malloc(3 * n * sizeof(double)), malloc(9 * n * sizeof(double)),
               calloc(3 * n, sizeof(double)), calloc(9 * n, sizeof(double))};
  return o;
}

static void g2p_out_free(g2p_out *o) { free(o->x), free(o->v), free(o->affine), free(o->dx), free(o->L); }

static void g2p_out_take(const mrn_particles *ps, int dim, g2p_out *o) {
  memcpy(o->x, ps->x, 3 * ps->n * sizeof(double));
  memcpy(o->v, ps->v, 3 * ps->n * sizeof(double));
  memcpy(o->affine, ps->affine, (size_t)(dim * dim) * ps->n * sizeof(double));
}

/* mode bit 0: increments to dx instead of moving; bit 1: gradients handed on
 * (mrn_g2p_then); mode 4: the gradient pass alone (mrn_gradient, from V~) */
static void check_g2p(kase *k, tally *t, int mode) {
  mrn_sim *sim = k->sim;
  const int dim = sim->dim, use_dx = mode & 1, use_L = mode & 2 || mode == 4;
  g2p_out f = g2p_out_new(sim->particles.n), r = g2p_out_new(sim->particles.n);
  const mrn_gradient_sink sink = {capture, f.L, MRN_PHASE_STRESS};
  particles_save(k, 0);
  long after_bad;
  if (mode == 4) mrn_gradient(&k->t, sim->grid.vel_new, &sink);
  else if (mode & 2) mrn_g2p_then(&k->t, DT, use_dx ? f.dx : NULL, &sink, NULL, &after_bad);
  else mrn_g2p(&k->t, DT, use_dx ? f.dx : NULL);
  g2p_out_take(&sim->particles, dim, &f);
  particles_save(k, 1);
  mrn_ref_g2p(&k->t, DT, use_dx ? r.dx : NULL, r.L);
  g2p_out_take(&sim->particles, dim, &r);
  if (mode == 4) { /* only grad v is the gradient pass's */
    memcpy(f.x, r.x, 3 * sim->particles.n * sizeof(double));
    memcpy(f.v, r.v, 3 * sim->particles.n * sizeof(double));
    memcpy(f.affine, r.affine, (size_t)(dim * dim) * sim->particles.n * sizeof(double));
  }
  particles_save(k, 1);
  g2p_compare(k, t, &f, &r, use_dx, use_L);
  g2p_out_free(&f), g2p_out_free(&r);
}

/* USF's material update and force in one pass (the sink leaves the stress
 * as it is): grad v from V~ and the internal force */
static void check_update_force(kase *k, tally *tp, tally *tg) {
  mrn_sim *sim = k->sim;
  if (!fast_config(&k->t.kernel)) return; /* (whether step.c would take it depends only on the particles' order) */
  g2p_out f = g2p_out_new(sim->particles.n), r = g2p_out_new(sim->particles.n);
  const mrn_gradient_sink sink = {capture, f.L, MRN_PHASE_STRESS};
  mrn_p2g(&k->t, 1, 0);
  mrn_update_force(&k->t, sim->grid.vel_new, &sink);
  mrn_transfer tr = k->t;
  tr.grid = &k->ref;
  mrn_ref_p2g(&tr, 0, 1);
  p2g_compare(k, tp, 0, 1);
  particles_save(k, 0);
  mrn_ref_g2p(&k->t, DT, r.dx, r.L);
  g2p_out_take(&sim->particles, sim->dim, &r);
  particles_save(k, 1);
  memcpy(f.x, r.x, 3 * sim->particles.n * sizeof(double));
  memcpy(f.v, r.v, 3 * sim->particles.n * sizeof(double));
  memcpy(f.affine, r.affine, (size_t)(sim->dim * sim->dim) * sim->particles.n * sizeof(double));
  memcpy(f.dx, r.dx, 3 * sim->particles.n * sizeof(double));
  g2p_compare(k, tg, &f, &r, 1, 1);
  g2p_out_free(&f), g2p_out_free(&r);
}

/* ---- the variants ------------------------------------------------------------------- */

/* the velocity and position updates, with XPIC's order */
static const int updates[][3] = {
    {MRN_VUPDATE_PIC, MRN_XUPDATE_GRID, 1},   {MRN_VUPDATE_PIC, MRN_XUPDATE_PARTICLE, 1},
    {MRN_VUPDATE_FLIP, MRN_XUPDATE_GRID, 1},  {MRN_VUPDATE_FLIP, MRN_XUPDATE_PARTICLE, 1},
    {MRN_VUPDATE_BLEND, MRN_XUPDATE_GRID, 1}, {MRN_VUPDATE_BLEND, MRN_XUPDATE_PARTICLE, 1},
    {MRN_VUPDATE_XPIC, MRN_XUPDATE_XPIC, 1},  {MRN_VUPDATE_XPIC, MRN_XUPDATE_XPIC, 3}};
enum { NU = sizeof updates / sizeof updates[0] };

/* scheme number i (0 ..): grid velocity i / NU, updates i % NU */
static int scheme_at(int i, int mls, mrn_scheme *s) {
  if (i >= 3 * NU) return 0;
  mrn_scheme_default(s);
  s->grid_velocity = (mrn_grid_velocity_kind)(i / NU);
  s->velocity_update = (mrn_velocity_update_kind)updates[i % NU][0];
  s->position_update = (mrn_position_update_kind)updates[i % NU][1];
  s->xpic_order = updates[i % NU][2];
  s->flip_fraction = s->velocity_update == MRN_VUPDATE_BLEND ? 0.7 : s->velocity_update == MRN_VUPDATE_FLIP;
  s->mls_gradient = mls;
  mrn_scheme_describe(s);
  CHECK(mrn_scheme_validate(s) == 0);
  return 1;
}

static void run_case(int dim, mrn_shape_kind shape, mrn_kernel_boundary face, int extra, int dense, tally *tp,
                     tally *tg) {
  kase k;
  kase_init(&k, make_sim(dim, shape, face, extra, dense));
  mrn_scheme s;
  for (int i = 0; scheme_at(i, extra == EXTRA_MLS, &s); i++) {
    k.sim->scheme = s;
    if (i == 0) kase_refresh(&k); /* the kernel options do not change from scheme to scheme */
    if (s.velocity_update == MRN_VUPDATE_PIC && s.position_update == MRN_XUPDATE_GRID) check_p2g(&k, tp);
    grid_state(&k);
    /* PIC (no dv gathered) and FLIP in every mode, the others in one */
    const int u = i % NU, all = u == 0 || u == 2;
    for (int mode = all ? 0 : u % 4; mode < (all ? 4 : u % 4 + 1); mode++) check_g2p(&k, tg, mode);
    if (i == 0) check_g2p(&k, tg, 4);
    if (i == 0) check_update_force(&k, tp, tg);
  }
  kase_free(&k);
}

int main(void) {
  static const char *const faces[] = {"extended", "truncated", "modified", "wls"};
  fused_ = fuses_multiply_add();
  printf("same order: bitwise / values, worst ulp (bound %g); other order or formula: values, worst ulp (bound %g)%s\n",
         fused_ ? FUSED_ULP : 0.0, BOUND_ULP, fused_ ? "; this build fuses multiply-adds" : "");
  for (int dim = 2; dim <= 3; dim++)
    for (int shape = 0; shape < MRN_SHAPE_KIND_COUNT; shape++)
      for (int face = 0; face < MRN_KERNEL_BOUNDARY_COUNT && mrn_shape_takes_dim(shape, dim); face++)
        for (int extra = 0; extra < EXTRA_COUNT; extra++) {
          tally tp = {0}, tg = {0};
          char where[96];
          snprintf(where, sizeof where, "%dD %s %s%s", dim, mrn_shape_info_of((mrn_shape_kind)shape)->name,
                   faces[face], extra_names[extra]);
          rng_state = 1000u * (unsigned)dim + 100u * (unsigned)shape + 10u * (unsigned)face + (unsigned)extra;
          for (int dense = 0; dense < 2; dense++) {
            where_ = where;
            run_case(dim, (mrn_shape_kind)shape, (mrn_kernel_boundary)face, extra, dense, &tp, &tg);
          }
          printf("%-40s P2G %6ld/%6ld %4.2f %6ld %5.2f | G2P %6ld/%6ld %4.2f %6ld %5.2f\n", where, tp.bitwise,
                 tp.general, tp.worst_general, tp.fast, tp.worst_fast, tg.bitwise, tg.general, tg.worst_general, tg.fast,
                 tg.worst_fast);
        }
  CHECK_DONE();
}

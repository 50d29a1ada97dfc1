#include "particles/seed.h"

#include <math.h>
#include <stdint.h>

#include "core/error.h"
#include "core/interrupt.h"

/* cell indices beyond this cannot be held exactly in a double */
#define SEED_MAX_CELL_INDEX 1e15

/* ---- Gauss-Legendre rules ---------------------------------------------- */

/* The non-negative roots of the Legendre polynomial P_n, ascending, and their
 * weights, evaluated in 50-digit arithmetic and rounded to 21 digits so that
 * every entry is the correctly rounded double (Newton's method in double
 * precision leaves the weights a few ulps off). Row n is the rule of order n. */
static const double gl_root[MRN_SEED_MAX_PER_AXIS + 1][4] = {
    {0},
    {0.0},
    {0.577350269189625764509},
    {0.0, 0.774596669241483377036},
    {0.339981043584856264803, 0.861136311594052575224},
    {0.0, 0.538469310105683091036, 0.906179845938663992798},
    {0.238619186083196908631, 0.661209386466264513661, 0.932469514203152027812},
    {0.0, 0.405845151377397166907, 0.741531185599394439864, 0.949107912342758524526},
    {0.183434642495649804939, 0.525532409916328985818, 0.796666477413626739592, 0.960289856497536231684},
};
static const double gl_weight[MRN_SEED_MAX_PER_AXIS + 1][4] = {
    {0},
    {2.0},
    {1.0},
    {0.888888888888888888889, 0.555555555555555555556},
    {0.652145154862546142627, 0.347854845137453857373},
    {0.568888888888888888889, 0.478628670499366468041, 0.236926885056189087514},
    {0.46791393457269104739, 0.36076157304813860757, 0.17132449237917034504},
    {0.417959183673469387755, 0.38183005050511894495, 0.279705391489276667901, 0.129484966168869693271},
    {0.362683783378361982965, 0.313706645877887287338, 0.222381034453374470544, 0.101228536290376259153},
};

void mrn_gauss_legendre(int n, double *points, double *weights) {
  if (n < 1 || n > MRN_SEED_MAX_PER_AXIS) return;
  /* mirror the table so that the rule is exactly symmetric, abscissae ascending */
  int half = n / 2;
  for (int k = 0; k < (n + 1) / 2; k++) {
    int hi = half + k, lo = n - 1 - hi; /* hi == lo for the middle root of an odd rule */
    points[lo] = -gl_root[n][k];
    points[hi] = gl_root[n][k]; /* after, so that a middle root is +0 */
    weights[hi] = weights[lo] = gl_weight[n][k];
  }
}

/* ---- seeding ----------------------------------------------------------- */

typedef struct {
  const mrn_grid *g;
  const mrn_region *r;
  int n;                                /* candidates per cell axis */
  double frac[MRN_SEED_MAX_PER_AXIS];   /* candidate offsets within a cell, in (0, 1) */
  double wfrac[MRN_SEED_MAX_PER_AXIS];  /* share of the cell width of each, summing to 1 */
  double cell_volume;                   /* h^dim */
  int64_t first[3], last[3];            /* cell index range; 0..0 along unused axes */
  mrn_seed_callback cb;
  void *user;
  long count;
} seeder;

static void sub_points(seeder *s, mrn_seed_placement placement) {
  if (placement == MRN_SEED_REGULAR) {
    for (int k = 0; k < s->n; k++) {
      s->frac[k] = (k + 0.5) / s->n;
      s->wfrac[k] = 1.0 / s->n;
    }
    return;
  }
  double xi[MRN_SEED_MAX_PER_AXIS], w[MRN_SEED_MAX_PER_AXIS];
  mrn_gauss_legendre(s->n, xi, w);
  for (int k = 0; k < s->n; k++) {
    s->frac[k] = 0.5 * (xi[k] + 1.0);
    s->wfrac[k] = 0.5 * w[k];
  }
}

/* Cells along axis d that overlap the region's bounding box; an unbounded
 * side is clipped to the grid. Sets *empty when no cell overlaps. */
static int axis_range(seeder *s, int d, int *empty) {
  const mrn_grid *g = s->g;
  double lo = s->r->lo[d], hi = s->r->hi[d];
  if (lo == HUGE_VAL || hi == -HUGE_VAL || lo > hi) {
    *empty = 1;
    return MRN_OK;
  }
  double a = isfinite(lo) ? floor((lo - g->origin[d]) * g->inv_cell) : 0.0;
  double b = isfinite(hi) ? ceil((hi - g->origin[d]) * g->inv_cell) - 1.0 : g->ncell[d] - 1.0;
  if (b < a) {
    *empty = 1;
    return MRN_OK;
  }
  if (fabs(a) > SEED_MAX_CELL_INDEX || fabs(b) > SEED_MAX_CELL_INDEX)
    return mrn_error("region extends outside the grid: its bounding box along axis %d, [%g, %g], "
                     "lies far beyond the domain [%g, %g]",
                     d + 1, lo, hi, g->origin[d], g->origin[d] + g->size[d]);
  s->first[d] = (int64_t)a;
  s->last[d] = (int64_t)b;
  return MRN_OK;
}

/* Fills first/last for every axis and the number of candidate points in
 * them (0 when nothing can be seeded). */
static int cell_ranges(seeder *s, double *candidates) {
  int dim = s->g->dim, empty = 0;
  *candidates = 1.0;
  for (int d = 0; d < 3; d++) {
    s->first[d] = s->last[d] = 0;
    if (d >= dim) continue;
    if (axis_range(s, d, &empty) != MRN_OK) return MRN_ERR;
    if (empty) {
      *candidates = 0.0;
      return MRN_OK;
    }
    *candidates *= (double)(s->last[d] - s->first[d] + 1) * s->n;
  }
  return MRN_OK;
}

static int outside_error(const mrn_grid *g, const double x[3]) {
  const double *o = g->origin, *sz = g->size;
  if (g->dim == 2)
    return mrn_error("region extends outside the grid: point (%g, %g) is inside the region but outside "
                     "the domain [%g, %g] x [%g, %g]",
                     x[0], x[1], o[0], o[0] + sz[0], o[1], o[1] + sz[1]);
  return mrn_error("region extends outside the grid: point (%g, %g, %g) is inside the region but outside "
                   "the domain [%g, %g] x [%g, %g] x [%g, %g]",
                   x[0], x[1], x[2], o[0], o[0] + sz[0], o[1], o[1] + sz[1], o[2], o[2] + sz[2]);
}

static int cell_outside_grid(const seeder *s, const int64_t c[3]) {
  for (int d = 0; d < s->g->dim; d++)
    if (c[d] < 0 || c[d] >= s->g->ncell[d]) return 1;
  return 0;
}

/* Tests the n^dim candidates of cell c, by halves of the cell: first the
 * half-cell (quadrant in 2D, octant in 3D) below the centre along every
 * axis, x's halves fastest, z's slowest; within each, z outermost and x
 * fastest. The particles whose quadratic B-spline stencils start at the
 * same node (those between the same two cell centres along each axis) then
 * follow one another in index order, and P2G sums them as one group
 * (kernels_impl.h, group_sum). A point at the centre counts as above it,
 * as the stencil does. */
static int seed_cell(seeder *s, const int64_t c[3]) {
  const mrn_grid *g = s->g;
  int dim = g->dim;
  int outside = cell_outside_grid(s, c);
  double lo[3];
  for (int d = 0; d < 3; d++) lo[d] = d < dim ? g->origin[d] + (double)c[d] * g->cell : 0.0;
  int upper[MRN_SEED_MAX_PER_AXIS]; /* the half of the cell point k lies in along an axis */
  for (int k = 0; k < s->n; k++) upper[k] = s->frac[k] >= 0.5;
  const int nz = dim == 3 ? s->n : 1;
  for (int hz = 0; hz < (dim == 3 ? 2 : 1); hz++)
    for (int hy = 0; hy < 2; hy++)
      for (int hx = 0; hx < 2; hx++)
        for (int kz = 0; kz < nz; kz++)
          for (int ky = 0; ky < s->n; ky++)
            for (int kx = 0; kx < s->n; kx++) {
              if ((dim == 3 && upper[kz] != hz) || upper[ky] != hy || upper[kx] != hx) continue;
              double x[3] = {lo[0] + s->frac[kx] * g->cell, lo[1] + s->frac[ky] * g->cell,
                             dim == 3 ? lo[2] + s->frac[kz] * g->cell : 0.0};
              int in = mrn_region_contains(s->r, x);
              if (in < 0) {
                /* a predicate that failed without saying why */
                if (!mrn_error_message()[0])
                  mrn_error("region: predicate failed at (%g, %g, %g)", x[0], x[1], x[2]);
                return MRN_ERR;
              }
              if (!in) continue;
              /* cells inside the grid hold their candidates strictly inside the domain */
              if (outside) return outside_error(g, x);
              double volume = s->cell_volume * s->wfrac[kx] * s->wfrac[ky] * (dim == 3 ? s->wfrac[kz] : 1.0);
              if (s->cb) {
                int rc = s->cb(s->user, x, volume);
                if (rc) return rc;
              }
              s->count++;
            }
  return MRN_OK;
}

static int seed_cells(seeder *s) {
  int64_t c[3];
  for (c[2] = s->first[2]; c[2] <= s->last[2]; c[2]++)
    for (c[1] = s->first[1]; c[1] <= s->last[1]; c[1]++) {
      /* a seeding of up to 1e9 points takes minutes: a signal stops it
       * between rows of cells (the caller drops what was added) */
      if (mrn_interrupt_pending())
        return mrn_error_code(MRN_ERR_INTERRUPTED, "interrupted by signal %d while seeding",
                              mrn_interrupt_pending());
      for (c[0] = s->first[0]; c[0] <= s->last[0]; c[0]++) {
        int rc = seed_cell(s, c);
        if (rc) return rc;
      }
    }
  return MRN_OK;
}

static int check_arguments(const mrn_grid *g, const mrn_region *r, int per_axis) {
  if (per_axis < 1 || per_axis > MRN_SEED_MAX_PER_AXIS)
    return mrn_error("particles per cell axis must be in 1..%d, got %d", MRN_SEED_MAX_PER_AXIS, per_axis);
  if (!g || !r) return mrn_error("seed: needs a grid and a region");
  if (r->dim == 3 && g->dim == 2) return mrn_error("seed: cannot seed a 3D region on a 2D grid");
  return MRN_OK;
}

int mrn_seed_candidates(const mrn_grid *g, const mrn_region *r, int per_axis, double *candidates) {
  *candidates = 0.0;
  if (check_arguments(g, r, per_axis) != MRN_OK) return MRN_ERR;
  seeder s = {.g = g, .r = r, .n = per_axis};
  return cell_ranges(&s, candidates);
}

/* *count is the number of points the callback accepted (returned 0 for),
 * also when seeding stops early. A NULL callback only counts. */
int mrn_seed(const mrn_grid *g, const mrn_region *r, int per_axis, mrn_seed_placement placement,
             mrn_seed_callback cb, void *user, long *count) {
  if (count) *count = 0;
  if (check_arguments(g, r, per_axis) != MRN_OK) return MRN_ERR;
  if (placement != MRN_SEED_GAUSS && placement != MRN_SEED_REGULAR)
    return mrn_error("seed: unknown placement %d", (int)placement);

  seeder s = {.g = g, .r = r, .n = per_axis, .cb = cb, .user = user};
  s.cell_volume = g->dim == 3 ? g->cell * g->cell * g->cell : g->cell * g->cell;
  sub_points(&s, placement);
  double candidates;
  if (cell_ranges(&s, &candidates) != MRN_OK) return MRN_ERR;
  if (candidates == 0.0) return MRN_OK;
  if (candidates > MRN_SEED_MAX_CANDIDATES)
    return mrn_error("region: its bounding box holds %.3g candidate points at %d per cell axis, more than the %.0e "
                     "one seeding tests (seed the region in parts)",
                     candidates, per_axis, MRN_SEED_MAX_CANDIDATES);

  mrn_error_clear(); /* so a predicate failure without a message can be told apart */
  int rc = seed_cells(&s);
  if (count) *count = s.count;
  return rc;
}

/* moraine: the active part of the grid (see active.h). */
#include "grid/active.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/parallel.h"
#include "grid/grid.h"

static void spans_to_ranges(mrn_grid_active *a, const mrn_grid *g) {
  size_t k = 0;
  long nodes = 0;
  for (size_t r = 0; r < a->nrows; r++) {
    if (a->lo[r] >= a->hi[r]) continue;
    long base = (long)(r % (size_t)g->nnode[1]) * g->stride[1] + (long)(r / (size_t)g->nnode[1]) * g->stride[2];
    a->range_lo[k] = base + a->lo[r];
    a->range_hi[k] = base + a->hi[r];
    nodes += a->hi[r] - a->lo[r];
    k++;
  }
  a->nranges = k;
  a->nodes = nodes;
}

mrn_grid_active *mrn_grid_active_new(const mrn_grid *g) {
  mrn_grid_active *a = calloc(1, sizeof *a);
  if (!a) {
    mrn_error("grid: out of memory");
    return NULL;
  }
  a->nrows = (size_t)g->nnode[1] * (size_t)g->nnode[2];
  a->lo = malloc(a->nrows * sizeof *a->lo);
  a->hi = malloc(a->nrows * sizeof *a->hi);
  a->new_lo = malloc(a->nrows * sizeof *a->new_lo);
  a->new_hi = malloc(a->nrows * sizeof *a->new_hi);
  a->range_lo = malloc(a->nrows * sizeof *a->range_lo);
  a->range_hi = malloc(a->nrows * sizeof *a->range_hi);
  a->range_sum = malloc(a->nrows * sizeof *a->range_sum);
  if (!a->lo || !a->hi || !a->new_lo || !a->new_hi || !a->range_lo || !a->range_hi || !a->range_sum) {
    mrn_grid_active_free(a);
    mrn_error("grid: out of memory");
    return NULL;
  }
  /* nothing is known about the nodal arrays yet */
  for (size_t r = 0; r < a->nrows; r++) {
    a->lo[r] = 0;
    a->hi[r] = g->nnode[0];
  }
  spans_to_ranges(a, g);
  return a;
}

void mrn_grid_active_free(mrn_grid_active *a) {
  if (!a) return;
  free(a->lo);
  free(a->hi);
  free(a->new_lo);
  free(a->new_hi);
  free(a->range_lo);
  free(a->range_hi);
  free(a->range_sum);
  free(a);
}

size_t mrn_grid_active_bytes(const mrn_grid *g) {
  const mrn_grid_active *a = g->active;
  if (!a) return 0;
  return sizeof *a + a->nrows * (4 * sizeof(int) + 2 * sizeof(long) + sizeof(double));
}

void mrn_grid_active_begin(mrn_grid *g) {
  mrn_grid_active *a = g->active;
  for (size_t r = 0; r < a->nrows; r++) {
    a->new_lo[r] = g->nnode[0];
    a->new_hi[r] = 0;
  }
}

void mrn_grid_active_all(mrn_grid *g) {
  mrn_grid_active *a = g->active;
  for (size_t r = 0; r < a->nrows; r++) {
    a->new_lo[r] = 0;
    a->new_hi[r] = g->nnode[0];
  }
}

/* zero `count` nodes from `first` in every array named, or in every array */
static void clear_nodes(mrn_grid *g, long first, long count, unsigned what, int all) {
  if (count <= 0) return;
  if (all || (what & MRN_CLEAR_MASS_MOM)) {
    memset(g->mass + first, 0, (size_t)count * sizeof(double));
    memset(g->mom + 3 * first, 0, 3 * (size_t)count * sizeof(double));
  }
  if (all || (what & MRN_CLEAR_FORCE)) memset(g->force + 3 * first, 0, 3 * (size_t)count * sizeof(double));
  if (all) {
    memset(g->vel + 3 * first, 0, 3 * (size_t)count * sizeof(double));
    memset(g->vel_new + 3 * first, 0, 3 * (size_t)count * sizeof(double));
  }
}

void mrn_grid_active_switch(mrn_grid *g, unsigned clear) {
  mrn_grid_active *a = g->active;
  const long rows = (long)a->nrows;
  /* the old spans measure the work (the new ones are alike) */
#pragma omp parallel for schedule(static) if (a->nodes > MRN_OMP_MIN_NODES)
  for (long r = 0; r < rows; r++) {
    const long base = (r % g->nnode[1]) * g->stride[1] + (r / g->nnode[1]) * g->stride[2];
    int ol = a->lo[r], oh = a->hi[r], nl = a->new_lo[r], nh = a->new_hi[r];
    if (nl >= nh) {
      nl = nh = 0;
      clear_nodes(g, base + ol, oh - ol, 0, 1);
    } else if (ol < oh) {
      clear_nodes(g, base + ol, (oh < nl ? oh : nl) - ol, 0, 1);
      int from = ol > nh ? ol : nh;
      clear_nodes(g, base + from, oh - from, 0, 1);
    }
    clear_nodes(g, base + nl, nh - nl, clear, 0);
    a->lo[r] = nl;
    a->hi[r] = nh;
  }
  spans_to_ranges(a, g);
}

/* [*lo, *hi) widened to cover [x0, x1) (an empty span becomes it) */
static void widen(int *lo, int *hi, int x0, int x1) {
  if (*lo >= *hi) {
    *lo = x0;
    *hi = x1;
    return;
  }
  if (x0 < *lo) *lo = x0;
  if (x1 > *hi) *hi = x1;
}

void mrn_grid_active_widen(mrn_grid *g, size_t row, int x0, int x1) {
  mrn_grid_active *a = g->active;
  if (x0 >= x1) return;
  widen(&a->lo[row], &a->hi[row], x0, x1);
  /* and the spans a switch without a new begin keeps (a P2G reusing the
   * binning): else it would clear what the halo sum added there */
  widen(&a->new_lo[row], &a->new_hi[row], x0, x1);
}

void mrn_grid_active_refresh(mrn_grid *g) { spans_to_ranges(g->active, g); }

mrn_node_ranges mrn_grid_active_ranges(const mrn_grid *g) {
  const mrn_grid_active *a = g->active;
  mrn_node_ranges r = {(long)a->nranges, a->range_lo, a->range_hi, a->range_sum, a->nodes};
  return r;
}

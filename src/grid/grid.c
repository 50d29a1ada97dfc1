#include "grid/grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <stdio.h>

#include "core/error.h"
#include "core/memory.h"
#include "grid/active.h"

int mrn_grid_init(mrn_grid *g, int dim, const double origin[3], const double size[3], double cell) {
  memset(g, 0, sizeof *g);
  if (dim != 2 && dim != 3) return mrn_error("grid: dimension must be 2 or 3, got %d", dim);
  if (!(cell > 0) || !isfinite(cell)) return mrn_error("grid: cell size must be > 0, got %s", mrn_num(cell).s);
  g->dim = dim;
  g->cell = cell;
  g->inv_cell = 1.0 / cell;
  g->pad = MRN_GRID_PAD;
  long total = 1;
  for (int d = 0; d < 3; d++) {
    if (d < dim) {
      if (!(size[d] > 0) || !isfinite(size[d]))
        return mrn_error("grid: size[%d] must be > 0, got %s", d + 1, mrn_num(size[d]).s);
      double cells = size[d] / cell;
      /* both bounds before rounding: lround of a huge or infinite count is undefined */
      if (cells < 1 - 1e-6)
        return mrn_error("grid: cell size %g is larger than the domain size %g along axis %d", cell, size[d], d + 1);
      if (!(cells <= 1000000.5)) return mrn_error("grid: %g cells along axis %d is more than 1e6", cells, d + 1);
      long nc = lround(cells);
      if (fabs(cells - (double)nc) > 1e-6)
        return mrn_error("grid: size %g along axis %d is not a whole number of cells of %g (%.6f cells)",
                         size[d], d + 1, cell, cells);
      g->ncell[d] = (int)nc;
      g->origin[d] = origin[d];
      g->size[d] = nc * cell;
      g->nnode[d] = (int)nc + 1 + 2 * g->pad;
    } else {
      g->ncell[d] = 0;
      g->origin[d] = 0;
      g->size[d] = 0;
      g->nnode[d] = 1;
    }
  }
  g->stride[0] = 1;
  g->stride[1] = g->nnode[0];
  g->stride[2] = (long)g->nnode[0] * g->nnode[1];
  g->own_lo = -g->pad;
  g->own_hi = g->ncell[dim - 1] + g->pad + 1;
  total = (long)g->nnode[0] * g->nnode[1] * g->nnode[2];
  if (total > 400000000L) return mrn_error("grid: %ld nodes is more than this build allows (4e8)", total);
  /* a grid whose arrays alone exceed the machine's memory (a cell size typed
   * a hundred times too small) is refused with the figures: 19 doubles per node */
  char what[64];
  snprintf(what, sizeof what, "grid: %ld nodes", total);
  if (mrn_memory_check(what, (double)total * 19 * sizeof(double), " (is the cell size right?)") != MRN_OK) return MRN_ERR;
  g->n = (size_t)total;
  g->mass = calloc(g->n, sizeof(double));
  g->mom = calloc(3 * g->n, sizeof(double));
  g->vel = calloc(3 * g->n, sizeof(double));
  g->vel_new = calloc(3 * g->n, sizeof(double));
  g->force = calloc(3 * g->n, sizeof(double));
  g->vel_star = calloc(3 * g->n, sizeof(double));
  g->work = calloc(3 * g->n, sizeof(double));
  g->contact = calloc(g->n, 1);
  g->touch = calloc(g->n, 1);
  if (!g->mass || !g->mom || !g->vel || !g->vel_new || !g->force || !g->vel_star || !g->work || !g->contact ||
      !g->touch) {
    mrn_grid_free(g);
    return mrn_error("grid: out of memory for %zu nodes", (size_t)total);
  }
  g->active = mrn_grid_active_new(g);
  if (!g->active) {
    mrn_grid_free(g);
    return mrn_error("grid: out of memory for %zu nodes", (size_t)total);
  }
  return MRN_OK;
}

void mrn_grid_free(mrn_grid *g) {
  free(g->mass);
  free(g->mom);
  free(g->vel);
  free(g->vel_new);
  free(g->force);
  free(g->vel_star);
  free(g->work);
  free(g->contact);
  free(g->touch);
  free(g->held);
  g->mass = g->mom = g->vel = g->vel_new = g->force = g->vel_star = g->work = NULL;
  g->contact = g->touch = NULL;
  g->held = NULL;
  mrn_grid_active_free(g->active);
  g->active = NULL;
}

void mrn_grid_clear(mrn_grid *g) {
  memset(g->mass, 0, g->n * sizeof(double));
  memset(g->mom, 0, 3 * g->n * sizeof(double));
  memset(g->force, 0, 3 * g->n * sizeof(double));
}

void mrn_grid_node_ijk(const mrn_grid *g, size_t idx, int ijk[3]) {
  long r = (long)idx;
  ijk[2] = (int)(r / g->stride[2]);
  r -= ijk[2] * g->stride[2];
  ijk[1] = (int)(r / g->stride[1]);
  ijk[0] = (int)(r - ijk[1] * g->stride[1]);
  for (int d = 0; d < 3; d++) ijk[d] = d < g->dim ? ijk[d] - g->pad : 0;
}

void mrn_grid_reach_box(const mrn_grid *g, const double *x, double reach, int lo[3], int hi[3]) {
  for (int d = 0; d < 3; d++) lo[d] = hi[d] = 0;
  for (int d = 0; d < g->dim; d++) {
    const double xi = (x[d] - g->origin[d]) * g->inv_cell;
    lo[d] = (int)floor(xi - reach) + 1;
    hi[d] = (int)ceil(xi + reach) - 1;
    if (lo[d] < -g->pad) lo[d] = -g->pad;
    if (hi[d] > g->ncell[d] + g->pad) hi[d] = g->ncell[d] + g->pad;
  }
}

void mrn_grid_node_position(const mrn_grid *g, size_t idx, double x[3]) {
  int ijk[3];
  mrn_grid_node_ijk(g, idx, ijk);
  for (int d = 0; d < 3; d++) x[d] = d < g->dim ? g->origin[d] + ijk[d] * g->cell : 0.0;
}

